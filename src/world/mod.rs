//! A world of bodies (docs/world.md): any number of spheres and flat walls, a uniform gravity, and the contacts
//! that follow, each located and measured as one impact is.
//!
//! [`driver`] runs the world: free flight in closed form ([`flight`]) until two bodies touch, then the island of
//! bodies that active contacts couple ([`island`]), segment by segment, keeping each contact's [`record`]: the
//! [`record::WorldOutcome`] its report is built from (`report::world`). [`sequential`] is the textbook's answer beside
//! the simulation: each contact alone and instantaneous, in the order they began. Running a world scene to its
//! report — and a world of two bodies without gravity as today's two-body impact — is [`crate::world_run`]'s, the
//! layer above.

pub mod broad;
pub mod coast;
pub mod driver;
pub mod flight;
pub mod island;
pub mod record;
pub mod sequential;
pub mod sites;

pub use driver::WorldError;
