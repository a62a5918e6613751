//! The validation cases, one module per benchmark, in one test binary:
//! each release test binary costs CI about 30–45 s of thin-LTO linking, so
//! the cases share one. Run one case with
//! `cargo test --release -p validation --test cases <module>:: -- --nocapture`.

mod axisymmetric_bar;
mod block_in_half_tube;
mod block_on_rigid_plane;
mod cantilever;
mod concentric_cylinders;
mod concentric_spheres;
mod contact_patch;
mod die_drawing;
mod dynamics;
mod elastoplastic_sphere;
mod flat_punch;
mod force_control;
mod hertz_cylinder;
mod hertz_sphere;
mod implicit_bar;
mod lame_cylinder;
mod large_strain;
mod manufactured_solution;
mod nafems_punch;
mod parallel_cylinders;
mod plastic_upsetting;
mod punch_probe;
mod rigid_cylinder;
mod shallow_ironing;
mod sphere_block;
mod strand_compacting;
mod twisting_blocks;
mod twisting_hemisphere;
mod uniform_stress;
mod wire_drawing;
mod wire_rolling;
mod without_tuning_keys;
