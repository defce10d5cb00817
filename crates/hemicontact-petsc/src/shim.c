/* The C side of hemicontact's PETSc bindings: a few functions with fixed-width argument
 * types (int64_t indices, double values) over PETSc's API, so that the Rust side never
 * depends on PetscInt's width, on PETSc's macros (PETSC_COMM_SELF, PetscCall) or on its
 * struct layouts. Every function returns a PETSc error code (0: success); the message of
 * the first error is kept for hc_last_error(). */

#include <petscksp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char last_error[2048];

/* Error handler: records the message of an error where it is raised (not the traceback
 * lines of the callers it returns through) instead of printing it. */
static PetscErrorCode record_error(MPI_Comm comm, int line, const char *func, const char *file,
                                   PetscErrorCode code, PetscErrorType type, const char *mess,
                                   void *ctx)
{
  (void)comm; (void)line; (void)file; (void)ctx;
  if (type == PETSC_ERROR_INITIAL) {
    snprintf(last_error, sizeof last_error, "%s (PETSc error %d in %s)", mess ? mess : "",
             (int)code, func ? func : "?");
  }
  return code;
}

const char *hc_last_error(void) { return last_error; }

static void finalize_at_exit(void)
{
  PetscBool finalized = PETSC_TRUE;
  if (PetscFinalized(&finalized) == 0 && !finalized) PetscFinalize();
}

/* PETSc and MPI, once per process: without PETSc's signal handler (a Ctrl-C stays the
 * application's), errors recorded rather than printed, finalized at exit. */
int hc_initialize(void)
{
  static int argc = 2;
  static char arg0[] = "hemicontact";
  static char arg1[] = "-no_signal_handler";
  static char *args[] = {arg0, arg1, NULL};
  static char **argv = args;
  PetscBool done = PETSC_FALSE;
  PetscErrorCode ierr = PetscInitialized(&done);
  if (ierr) return (int)ierr;
  if (done) return 0;
  ierr = PetscInitialize(&argc, &argv, NULL, NULL);
  if (ierr) {
    snprintf(last_error, sizeof last_error, "PetscInitialize failed (PETSc error %d)", (int)ierr);
    return (int)ierr;
  }
  ierr = PetscPushErrorHandler(record_error, NULL);
  if (ierr) return (int)ierr;
  atexit(finalize_at_exit);
  return 0;
}

/* The PETSc version as major * 10000 + minor * 100 + subminor, and sizeof(PetscInt). */
int hc_version(void) { return PETSC_VERSION_MAJOR * 10000 + PETSC_VERSION_MINOR * 100 + PETSC_VERSION_SUBMINOR; }
int hc_int_size(void) { return (int)sizeof(PetscInt); }

/* This process's rank and the number of processes of PETSC_COMM_WORLD (MPI_COMM_WORLD). */
int hc_world(int *rank, int *size)
{
  PetscErrorCode ierr = (PetscErrorCode)MPI_Comm_rank(PETSC_COMM_WORLD, rank);
  if (!ierr) ierr = (PetscErrorCode)MPI_Comm_size(PETSC_COMM_WORLD, size);
  return (int)ierr;
}

/* The number of processes of PETSC_COMM_WORLD that share this process's machine (its
   shared-memory node, MPI_COMM_TYPE_SHARED). Collective. */
int hc_ranks_on_node(int *count)
{
  MPI_Comm node;
  int      ierr = MPI_Comm_split_type(PETSC_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  if (ierr) return ierr;
  ierr = MPI_Comm_size(node, count);
  MPI_Comm_free(&node);
  return ierr;
}

/* values <- the sum (op 0), maximum (1) or minimum (2) over the processes, element-wise. */
int hc_allreduce(double *values, int64_t n, int op)
{
  MPI_Op mpi_op = op == 1 ? MPI_MAX : op == 2 ? MPI_MIN : MPI_SUM;
  return MPI_Allreduce(MPI_IN_PLACE, values, (int)n, MPI_DOUBLE, mpi_op, PETSC_COMM_WORLD);
}

/* global <- the concatenation of every process's local values in rank order; n_global is
 * the length of global, checked against the sum of the local lengths. */
int hc_allgatherv(const double *local, int64_t n_local, double *global, int64_t n_global)
{
  int size, count = (int)n_local, *counts, *displs, ierr;
  int64_t total = 0;
  ierr = MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (ierr) return ierr;
  counts = (int *)malloc(2 * (size_t)size * sizeof(int));
  if (!counts) return PETSC_ERR_MEM;
  displs = counts + size;
  ierr = MPI_Allgather(&count, 1, MPI_INT, counts, 1, MPI_INT, PETSC_COMM_WORLD);
  for (int r = 0; !ierr && r < size; r++) {
    displs[r] = (int)total;
    total += counts[r];
  }
  if (!ierr && total != n_global) {
    snprintf(last_error, sizeof last_error, "allgather of %lld values into %lld", (long long)total, (long long)n_global);
    ierr = PETSC_ERR_ARG_SIZ;
  }
  if (!ierr) ierr = MPI_Allgatherv(local, count, MPI_DOUBLE, global, counts, displs, MPI_DOUBLE, PETSC_COMM_WORLD);
  free(counts);
  return ierr;
}

/* Ends every process of PETSC_COMM_WORLD with the exit code. */
void hc_abort(int code) { MPI_Abort(PETSC_COMM_WORLD, code); }

/* A symmetric positive definite system on a fixed pattern with its Krylov solver. */
typedef struct {
  Mat A;
  KSP ksp;
  Vec x, b;
  PetscInt n;     /* rows of this process */
  PetscInt first; /* global number of its first row */
  PetscInt *row_ptr, *cols;
  PetscBool fixed_rtol;  /* the options set -ksp_rtol: the per-solve tolerance is not imposed */
  PetscBool fixed_maxit; /* the options set -ksp_max_it: the per-solve cap is not imposed */
  PetscBool true_residual_cg; /* CG on the unpreconditioned residual: a kept (lagged)
                               * preconditioner cannot give a wrong answer, only iterations */
  VecScatter ghost_scatter;   /* from x to this process's ghost rows (NULL: none set) */
  Vec ghosts;                 /* the ghost rows' values, sequential */
} hc_system;

static PetscErrorCode copy_indices(PetscInt count, const int64_t *from, PetscInt **to)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(count > 0 ? count : 1, to));
  for (PetscInt k = 0; k < count; k++) {
    PetscCheck(from[k] >= 0 && from[k] <= (int64_t)PETSC_MAX_INT, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "index %lld does not fit PETSc's %d-byte integers", (long long)from[k], (int)sizeof(PetscInt));
    (*to)[k] = (PetscInt)from[k];
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode system_create(int64_t n, int64_t n_global, int64_t first, int64_t block_size,
                                    const int64_t *row_ptr, const int64_t *cols,
                                    const double *coordinates, const char *prefix,
                                    const char *options, int distributed, hc_system **out)
{
  MPI_Comm comm = distributed ? PETSC_COMM_WORLD : PETSC_COMM_SELF;
  hc_system *s;
  Vec coords;
  MatNullSpace near_null;
  PC pc;
  KSPType ksp_type;
  PetscBool has_norm, is_cg, has_ptap;
  PetscScalar *array;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  *out = s;
  s->n = (PetscInt)n;
  s->first = (PetscInt)first;
  PetscCall(copy_indices(n + 1, row_ptr, &s->row_ptr));
  PetscCall(copy_indices(row_ptr[n], cols, &s->cols));

  /* The matrix: AIJ with the pattern preallocated exactly, in blocks of one node's DOFs;
   * distributed, each process holds its rows (columns in global numbers). */
  PetscCall(MatCreate(comm, &s->A));
  PetscCall(MatSetSizes(s->A, s->n, s->n, (PetscInt)n_global, (PetscInt)n_global));
  PetscCall(MatSetBlockSize(s->A, (PetscInt)block_size));
  PetscCall(MatSetType(s->A, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocationCSR(s->A, s->row_ptr, s->cols, NULL));
  PetscCall(MatMPIAIJSetPreallocationCSR(s->A, s->row_ptr, s->cols, NULL));
  PetscCall(MatSetOption(s->A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatSetOption(s->A, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(s->A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PetscCall(MatSetOption(s->A, MAT_SPD, PETSC_TRUE));
  PetscCall(MatSetOption(s->A, MAT_SPD_ETERNAL, PETSC_TRUE));

  /* The rigid-body modes of the nodes' coordinates: the near-null space of elasticity that
   * smoothed aggregation interpolates exactly. */
  PetscCall(MatCreateVecs(s->A, &s->x, &s->b));
  PetscCall(VecDuplicate(s->x, &coords));
  PetscCall(VecSetBlockSize(coords, (PetscInt)block_size));
  PetscCall(VecGetArray(coords, &array));
  for (PetscInt k = 0; k < s->n; k++) array[k] = coordinates[k];
  PetscCall(VecRestoreArray(coords, &array));
  PetscCall(MatNullSpaceCreateRigidBody(coords, &near_null));
  PetscCall(MatSetNearNullSpace(s->A, near_null));
  PetscCall(MatNullSpaceDestroy(&near_null));
  PetscCall(VecDestroy(&coords));

  /* The defaults (CG + GAMG), then the user's options under this system's prefix. GAMG
   * builds a new interpolation at every set-up: reusing it (-pc_gamg_reuse_interpolation,
   * on by default in PETSc 3.18) was measured to make the V-cycle indefinite on the
   * contact problems of hemicontact, whose matrix changes between Newton steps. */
  /* On three processes or more, PETSc's default triple product P^T A P (GAMG's coarse
   * matrices) adds the contributions other processes send in the order they arrive, so the
   * last bits of the answer would change from run to run. The all-at-once product adds
   * them in a fixed order (measured: identical bits in every run, set-ups slower). It is a
   * global option of the process, kept when PETSC_OPTIONS names another. */
  PetscCall(MPI_Comm_size(comm, &size));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-matptap_via", &has_ptap));
  if (size >= 3 && !has_ptap) PetscCall(PetscOptionsSetValue(NULL, "-matptap_via", "allatonce"));
  PetscCall(KSPCreate(comm, &s->ksp));
  PetscCall(KSPSetOptionsPrefix(s->ksp, prefix));
  PetscCall(KSPSetOperators(s->ksp, s->A, s->A));
  PetscCall(KSPSetType(s->ksp, KSPCG));
  PetscCall(KSPGetPC(s->ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscCall(PCGAMGSetReuseInterpolation(pc, PETSC_FALSE));
  PetscCall(PetscOptionsPrefixPush(NULL, prefix));
  PetscCall(PetscOptionsInsertString(NULL, options));
  PetscCall(PetscOptionsPrefixPop(NULL));
  PetscCall(KSPSetFromOptions(s->ksp));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-ksp_rtol", &s->fixed_rtol));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-ksp_max_it", &s->fixed_maxit));
  /* CG measures the true residual ||b - A x|| / ||b||, the relative residual the Newton
   * method asks for, unless the options chose another norm. */
  PetscCall(PetscOptionsHasName(NULL, prefix, "-ksp_norm_type", &has_norm));
  PetscCall(KSPGetType(s->ksp, &ksp_type));
  PetscCall(PetscStrcmp(ksp_type, KSPCG, &is_cg));
  if (is_cg && !has_norm) PetscCall(KSPSetNormType(s->ksp, KSP_NORM_UNPRECONDITIONED));
  s->true_residual_cg = (PetscBool)(is_cg && !has_norm);
  PetscFunctionReturn(0);
}

void hc_system_destroy(hc_system *s)
{
  if (!s) return;
  KSPDestroy(&s->ksp);
  MatDestroy(&s->A);
  VecDestroy(&s->x);
  VecDestroy(&s->b);
  VecScatterDestroy(&s->ghost_scatter);
  VecDestroy(&s->ghosts);
  PetscFree(s->row_ptr);
  PetscFree(s->cols);
  PetscFree(s);
}

/* Creates the system of order n_global, of which this process holds the n rows from
 * global row first on, with their CSR pattern (row_ptr, cols) (both triangles, sorted
 * global columns), the nodes' coordinates of these rows in DOF order (block_size per node)
 * for the rigid-body modes, the options prefix and the options string: on
 * PETSC_COMM_WORLD (collective) if distributed, else on PETSC_COMM_SELF (n = n_global). */
int hc_system_create(int64_t n, int64_t n_global, int64_t first, int64_t block_size,
                     const int64_t *row_ptr, const int64_t *cols, const double *coordinates,
                     const char *prefix, const char *options, int distributed, hc_system **out)
{
  *out = NULL;
  PetscErrorCode ierr = system_create(n, n_global, first, block_size, row_ptr, cols, coordinates,
                                      prefix, options, distributed, out);
  if (ierr) {
    hc_system_destroy(*out);
    *out = NULL;
  }
  return (int)ierr;
}

static PetscErrorCode set_values(hc_system *s, const double *values)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < s->n; i++) {
    PetscInt row = s->first + i, start = s->row_ptr[i], count = s->row_ptr[i + 1] - start;
    PetscCall(MatSetValues(s->A, 1, &row, count, s->cols + start, values + start, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(s->A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(s->A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* Replaces the matrix values (CSR order of the pattern). The preconditioner is not touched:
 * hc_system_setup() builds it for them, or a solve with reuse keeps the old one. */
int hc_system_set_values(hc_system *s, const double *values) { return (int)set_values(s, values); }

static PetscErrorCode setup(hc_system *s)
{
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPSetReusePreconditioner(s->ksp, PETSC_FALSE));
  PetscCall(KSPSetUp(s->ksp));
  PetscCall(KSPGetPC(s->ksp, &pc));
  PetscCall(PCSetUp(pc));
  PetscFunctionReturn(0);
}

/* Sets the preconditioner up for the current matrix values. */
int hc_system_setup(hc_system *s) { return (int)setup(s); }

/* Whether the KSP is CG measuring the true residual (then a kept preconditioner changes the
 * iterations, never the answer's accuracy). */
int hc_system_can_keep_preconditioner(hc_system *s) { return (int)s->true_residual_cg; }

static PetscErrorCode solve(hc_system *s, double rtol, int64_t max_iterations, int keep,
                            const double *b, double *x, int64_t *iterations, int *reason,
                            double *residual)
{
  PetscScalar *array;
  const PetscScalar *result;
  PetscInt its;
  PetscReal rnorm;
  KSPConvergedReason why;

  PetscFunctionBeginUser;
  PetscCall(KSPSetReusePreconditioner(s->ksp, keep ? PETSC_TRUE : PETSC_FALSE));
  if (!s->fixed_rtol) PetscCall(KSPSetTolerances(s->ksp, rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  if (!s->fixed_maxit && max_iterations > 0)
    PetscCall(KSPSetTolerances(s->ksp, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, (PetscInt)max_iterations));
  PetscCall(VecGetArray(s->b, &array));
  for (PetscInt k = 0; k < s->n; k++) array[k] = b[k];
  PetscCall(VecRestoreArray(s->b, &array));
  PetscCall(KSPSolve(s->ksp, s->b, s->x));
  PetscCall(VecGetArrayRead(s->x, &result));
  for (PetscInt k = 0; k < s->n; k++) x[k] = result[k];
  PetscCall(VecRestoreArrayRead(s->x, &result));
  PetscCall(KSPGetIterationNumber(s->ksp, &its));
  PetscCall(KSPGetConvergedReason(s->ksp, &why));
  PetscCall(KSPGetResidualNorm(s->ksp, &rnorm));
  *iterations = (int64_t)its;
  *reason = (int)why;
  *residual = (double)rnorm;
  PetscFunctionReturn(0);
}

/* Solves A x = b from zero to the relative residual rtol in at most max_iterations
 * iterations (unless the options fixed -ksp_rtol or -ksp_max_it), with the preconditioner
 * kept as it is (keep != 0) or set up for changed values. The iterations, KSP's converged
 * reason (negative: diverged) and the final residual norm (in the KSP's norm) are
 * returned. */
int hc_system_solve(hc_system *s, double rtol, int64_t max_iterations, int keep, const double *b,
                    double *x, int64_t *iterations, int *reason, double *residual)
{
  return (int)solve(s, rtol, max_iterations, keep, b, x, iterations, reason, residual);
}

static PetscErrorCode set_ghosts(hc_system *s, int64_t n, const int64_t *rows)
{
  PetscInt *indices;
  IS is;

  PetscFunctionBeginUser;
  PetscCall(VecScatterDestroy(&s->ghost_scatter));
  PetscCall(VecDestroy(&s->ghosts));
  PetscCall(copy_indices((PetscInt)n, rows, &indices));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)n, indices, PETSC_OWN_POINTER, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, (PetscInt)n, &s->ghosts));
  PetscCall(VecScatterCreate(s->x, is, s->ghosts, NULL, &s->ghost_scatter));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* Sets the n rows (global numbers, any process's) whose values of the last solution
 * hc_system_ghost_values() fetches: PETSc's scatter from the distributed solution vector
 * to a sequential vector of those rows, built once (collective). */
int hc_system_set_ghosts(hc_system *s, int64_t n, const int64_t *rows)
{
  return (int)set_ghosts(s, n, rows);
}

static PetscErrorCode ghost_values(hc_system *s, double *out)
{
  const PetscScalar *values;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCheck(s->ghost_scatter, PETSC_COMM_SELF, PETSC_ERR_ORDER, "no ghost rows were set");
  PetscCall(VecScatterBegin(s->ghost_scatter, s->x, s->ghosts, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(s->ghost_scatter, s->x, s->ghosts, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetLocalSize(s->ghosts, &n));
  PetscCall(VecGetArrayRead(s->ghosts, &values));
  for (PetscInt k = 0; k < n; k++) out[k] = values[k];
  PetscCall(VecRestoreArrayRead(s->ghosts, &values));
  PetscFunctionReturn(0);
}

/* The values of the last solution at the rows set by hc_system_set_ghosts(), in their
 * order, from the processes that hold them (collective). */
int hc_system_ghost_values(hc_system *s, double *out) { return (int)ghost_values(s, out); }

/* The name of a KSP converged reason. */
const char *hc_converged_reason(int reason) { return KSPConvergedReasons[reason]; }

/* "ksp <type>, pc <type>[, <factor package>]" into buf. */
int hc_system_describe(hc_system *s, char *buf, size_t size)
{
  KSPType ksp_type;
  PCType pc_type;
  MatSolverType package = NULL;
  PC pc;
  PetscErrorCode ierr = KSPGetType(s->ksp, &ksp_type);
  if (!ierr) ierr = KSPGetPC(s->ksp, &pc);
  if (!ierr) ierr = PCGetType(pc, &pc_type);
  if (ierr) return (int)ierr;
  PCFactorGetMatSolverType(pc, &package);
  snprintf(buf, size, "ksp %s, pc %s%s%s", ksp_type ? ksp_type : "?", pc_type ? pc_type : "?",
           package ? ", " : "", package ? package : "");
  return 0;
}

#ifdef HC_HAVE_SCOTCH
#include <scotch.h>

/* Sequential Scotch in a deterministic context (the same graph gives the same parts, whatever
 * its threads do): returns Scotch's error code, 0 on success. */
static int scotch_partition(SCOTCH_Num n, const SCOTCH_Num *xadj, const SCOTCH_Num *adjncy,
                            SCOTCH_Num nparts, SCOTCH_Num *parts)
{
  SCOTCH_Context context;
  SCOTCH_Graph graph, bound;
  SCOTCH_Strat strategy;
  int ierr;
  if ((ierr = SCOTCH_contextInit(&context))) return ierr;
  SCOTCH_contextRandomSeed(&context, 1);
  ierr = SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1);
  if (!ierr) ierr = SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1);
  if (!ierr) ierr = SCOTCH_graphInit(&graph);
  if (!ierr) {
    ierr = SCOTCH_graphBuild(&graph, 0, n, xadj, NULL, NULL, NULL, xadj[n], adjncy, NULL);
    if (!ierr) ierr = SCOTCH_graphInit(&bound);
    if (!ierr) {
      ierr = SCOTCH_contextBindGraph(&context, &graph, &bound);
      if (!ierr) ierr = SCOTCH_stratInit(&strategy);
      if (!ierr) {
        ierr = SCOTCH_stratGraphMapBuild(&strategy, SCOTCH_STRATQUALITY, nparts, 0.03);
        if (!ierr) ierr = SCOTCH_graphPart(&bound, nparts, &strategy, parts);
        SCOTCH_stratExit(&strategy);
      }
      SCOTCH_graphExit(&bound);
    }
    SCOTCH_graphExit(&graph);
  }
  SCOTCH_contextExit(&context);
  return ierr;
}
#endif

/* Splits the graph of n vertices with adjacency lists xadj/adjncy (CSR, no self-loops,
 * symmetric) into nparts parts with Scotch (the sequential library PT-Scotch is built on),
 * on this process alone: parts[v] is the part of vertex v. */
int hc_partition(int64_t n, const int64_t *xadj, const int64_t *adjncy, int64_t nparts,
                 int64_t *parts)
{
#ifdef HC_HAVE_SCOTCH
  SCOTCH_Num *x = malloc(sizeof(SCOTCH_Num) * (size_t)(n + 1));
  SCOTCH_Num *a = malloc(sizeof(SCOTCH_Num) * (size_t)(xadj[n] > 0 ? xadj[n] : 1));
  SCOTCH_Num *p = malloc(sizeof(SCOTCH_Num) * (size_t)(n > 0 ? n : 1));
  int ierr = (!x || !a || !p) ? PETSC_ERR_MEM : 0;
  if (!ierr && (xadj[n] > (int64_t)INT32_MAX || nparts > (int64_t)INT32_MAX) && sizeof(SCOTCH_Num) == 4) ierr = PETSC_ERR_ARG_OUTOFRANGE;
  if (!ierr) {
    for (int64_t k = 0; k <= n; k++) x[k] = (SCOTCH_Num)xadj[k];
    for (int64_t k = 0; k < xadj[n]; k++) a[k] = (SCOTCH_Num)adjncy[k];
    ierr = scotch_partition((SCOTCH_Num)n, x, a, (SCOTCH_Num)nparts, p);
    if (ierr) snprintf(last_error, sizeof last_error, "Scotch could not partition the graph (error %d)", ierr);
    else for (int64_t k = 0; k < n; k++) parts[k] = (int64_t)p[k];
  }
  free(x);
  free(a);
  free(p);
  return ierr;
#else
  (void)n; (void)xadj; (void)adjncy; (void)nparts; (void)parts;
  snprintf(last_error, sizeof last_error, "this build of hemicontact has no Scotch: its header scotch.h was not found when it was built (on Debian: apt-get install libscotch-dev, then rebuild)");
  return PETSC_ERR_SUP;
#endif
}
