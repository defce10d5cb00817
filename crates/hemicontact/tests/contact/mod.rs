//! Contact with a foundation or a rigid obstacle: the pointwise normal and friction laws, user-defined laws, corners, obstacles (fixed and moving), Hertz, the exact constraints and the contact totals.

mod contact_laws;
mod contact_totals;
mod corners;
mod custom_friction;
mod custom_normal;
mod exact_constraints;
mod friction_input;
mod friction_term;
mod hertz;
mod moving_obstacles;
mod obstacle;
mod obstacle_placement;
