pub mod golden;
pub mod sim;
