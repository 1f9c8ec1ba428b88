//! The closed loop: a controller driving a plant tick by tick, through a
//! [`PlantLink`] that hides where the plant runs (in this process, or in
//! another process over iceoryx2 shared memory).

mod closed_loop_run;
mod control_record;
mod cut_story;
mod in_process;
mod loop_setup;
mod plant_link;
mod runner;
mod series_record;
mod series_stream;
mod series_writer;

pub use closed_loop_run::{
    RunOutput, run_closed_loop, run_closed_loop_on, run_closed_loop_recorded,
};
pub use control_record::{ControlSample, TickTimes};
pub use cut_story::CutStory;
pub use in_process::InProcessPlant;
pub use loop_setup::{
    LoopSetup, check_on_edge, cut_task, make_controller, make_plant, mpc_cutting_ratio,
    mpc_profile, mpc_start,
};
pub use plant_link::{LinkAnswer, LinkError, PlantLink};
pub use runner::{
    LOOP_RECORD_BYTES, LoopCut, LoopEnd, LoopOutput, record_capacity, run_loop, run_loop_recorded,
};
pub use series_stream::{DroppedRows, LoopRecorder, NoRecorder, QUEUE_RECORDS, SeriesStream};
pub use series_writer::FLUSH_PERIOD;
