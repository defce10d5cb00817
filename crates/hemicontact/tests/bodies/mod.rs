//! Contact between deformable bodies, and bodies whose rigid motions only contact or friction hold: patch tests, Hertz and Cattaneo–Mindlin between two bodies, a fault, the rigid drop, friction-held blocks.

mod fault;
mod held_by_friction;
mod hertz_two_bodies;
mod rigid;
mod rigid_drop;
mod two_bodies;
