//! dnsr-bench's parts: scenes, the timed runs, the copy roofline, the byte model and the report.

pub mod copy;
pub mod device;
pub mod json;
pub mod model;
pub mod report;
pub mod run;
pub mod scenes;
pub mod stats;
