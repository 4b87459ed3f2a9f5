//! Solving the model: global assembly and linear solves, statics (with the catenary start), the
//! energy–momentum time step, what users read off a state, and the record of a run.
pub mod assembly;
pub mod band_lu;
pub mod block_lu;
pub mod catenary;
pub mod contact;
pub mod dynamics;
pub mod energy;
pub mod friction;
pub mod history;
pub mod laid_catenary;
pub mod lay_summary;
pub mod linsolve;
pub mod pay_out;
pub mod pool;
pub mod response;
pub mod rod_step;
pub mod rollers;
pub mod statics;
#[cfg(test)]
mod test_support;
pub mod window_lu;
