//! Stiction's integration and validation tests, one module per subject, built as one test
//! binary (`cargo test -p stiction-tests --test validation`; one module's tests:
//! `cargo test -p stiction-tests --test validation lennard_jones::`). One binary links once
//! instead of once per file, and its harness runs any two of the tests at once, where a binary
//! per file ran one after another, each on 1.0 to 1.4 cores. Tests that write a run's files
//! claim their own folder under `target/test-out` with [`stiction_tests::claim_output_dir`].

mod arc_length;
mod bad_input;
mod builder;
mod calculix_benchmark;
mod cohesive_elements;
mod cold_weld;
mod convergence;
mod dcb;
mod dissipation_control;
mod elastic_references;
mod footprint;
mod footprint_correction;
mod greenwood_tripp;
mod greenwood_williamson;
mod hertz;
mod hill_sphere;
mod jackson_green;
mod lennard_jones;
mod mass;
mod mesh_and_output;
mod patch;
mod perfectly_plastic_neck;
mod plugins;
mod restart;
mod rough_sphere;
mod snap;
mod snap_and_crawl_rules;
mod solver_threads;
mod tangent_and_newton;
mod tangent_predictor;
mod tangent_switch;
