pub mod golden;
pub mod magnetic;
pub mod native;
pub mod rig_sim;
pub mod sim;
