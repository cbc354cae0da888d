pub mod golden;
pub mod native;
pub mod sim;
