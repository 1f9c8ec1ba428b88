//! shearcut, the application: command line, scenario config, plots, and (as
//! they land) the plant and controller processes, the iceoryx2 transport and
//! run orchestration.

pub mod angle_stream;
pub mod cli;
pub mod closed_loop;
pub mod commands;
pub mod constant_ratio;
pub mod controller_choice;
pub mod controller_settings;
pub mod csv_stream;
pub mod cut_record;
pub mod cut_stream;
pub mod error;
pub mod logging;
pub mod object_profile;
pub mod plot;
pub mod progress;
pub mod result_file;
pub mod run_dir;
pub mod run_replica;
pub mod scenario;
pub mod surrogates;
pub mod trajectory_cases;
pub mod transport;
pub mod tune;
