//! The one integration-test binary of the experts on a live whiteboard, in this process and as other processes.

mod experts;
mod programs;
