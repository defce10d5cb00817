//! Finds PETSc through pkg-config (`PETSc.pc`, or `petsc.pc`), and the MPI headers it
//! includes (Debian's `PETSc.pc` names neither OpenMPI's include nor its library folder:
//! `ompi-c`, then `mpich`, are probed too), then compiles the C shim `src/shim.c`.
//!
//! `PKG_CONFIG_PATH` selects another PETSc (e.g. `$PETSC_DIR/$PETSC_ARCH/lib/pkgconfig`).

fn probe(names: &[&str]) -> Option<pkg_config::Library> {
    names.iter().find_map(|name| {
        pkg_config::Config::new()
            .cargo_metadata(false)
            .probe(name)
            .ok()
    })
}

fn main() {
    println!("cargo:rerun-if-changed=src/shim.c");
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    let Some(petsc) = probe(&["PETSc", "petsc"]) else {
        panic!(
            "PETSc not found by pkg-config (PETSc.pc or petsc.pc). On Debian or Ubuntu: \
             apt-get install petsc-dev pkg-config; elsewhere set PKG_CONFIG_PATH to \
             $PETSC_DIR/$PETSC_ARCH/lib/pkgconfig. See docs/distributed.md."
        )
    };
    let mpi = probe(&["ompi-c", "mpich", "mpi"]);
    let mut shim = cc::Build::new();
    shim.file("src/shim.c").warnings(true);
    for lib in std::iter::once(&petsc).chain(mpi.as_ref()) {
        for path in &lib.include_paths {
            shim.include(path);
        }
    }
    // Scotch (the sequential library PT-Scotch is built on), if its header is found: the
    // mesh partitioner.
    let scotch = petsc
        .include_paths
        .iter()
        .map(|dir| dir.join("scotch"))
        .chain(petsc.include_paths.iter().cloned())
        .chain([std::path::PathBuf::from("/usr/include/scotch")])
        .find(|dir| dir.join("scotch.h").is_file());
    if let Some(dir) = &scotch {
        shim.include(dir).define("HC_HAVE_SCOTCH", None);
    }
    // The shim first (it is static and needs PETSc), then PETSc and MPI.
    shim.compile("hemicontact_petsc_shim");
    if scotch.is_some() {
        println!("cargo:rustc-link-lib=scotch");
        println!("cargo:rustc-link-lib=scotcherr");
    }
    for lib in std::iter::once(&petsc).chain(mpi.as_ref()) {
        for path in &lib.link_paths {
            println!("cargo:rustc-link-search=native={}", path.display());
        }
        for name in &lib.libs {
            println!("cargo:rustc-link-lib={name}");
        }
    }
    println!("cargo:version={}", petsc.version);
}
