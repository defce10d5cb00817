//! The paper's model and its convergence study.

mod paper_model;
mod paper_study_regression;
mod study;
