pub mod golden;
pub mod magnetic;
pub mod native;
pub mod sim;
