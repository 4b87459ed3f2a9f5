//! The vessel's wave-frequency motion (from its RAOs) over a step: the offsets at the step's start and end.
use crate::error::Result;
use crate::model::Model;
use crate::vessel::wave_motion::{station, WaveMotion, WaveOffset};

/// The vessel's wave-frequency motion and its offsets at the state's time and at the current step's end.
#[derive(Debug, Clone)]
pub struct VesselWaves {
    pub motion: WaveMotion,
    pub now: WaveOffset,
    pub next: WaveOffset,
}

impl VesselWaves {
    /// The motion of the vessel of `model` in its sea, if both exist and the vessel has RAOs, at time t.
    pub fn new(model: &Model, time: f64) -> Result<Option<Self>> {
        let (Some(field), Some(attachment)) = (&model.waves, &model.vessel) else {
            return Ok(None);
        };
        let Some(raos) = &attachment.vessel.raos else {
            return Ok(None);
        };
        let motion = WaveMotion::new(field, raos)?;
        let now = motion.offset(time, &station(attachment, time)?)?;
        Ok(Some(VesselWaves {
            motion,
            now,
            next: now,
        }))
    }
}
