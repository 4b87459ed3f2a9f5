//! Thin PyO3 layer over the `pipelay` engine: conversions, error mapping, GIL release.
mod callables;
mod capability;
mod convert;
mod errors;
mod lay;
mod material;
mod model;
mod raos;
mod reeling;
mod results;
mod seabed;
mod simulation;
mod stages;
mod state;
mod station_keeping;
mod structure;
mod vessel;
mod waves;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("InputError", py.get_type::<errors::InputError>())?;
    m.add(
        "ConvergenceError",
        py.get_type::<errors::ConvergenceError>(),
    )?;
    m.add_class::<structure::Clump>()?;
    m.add_class::<structure::Coating>()?;
    m.add_class::<structure::Section>()?;
    m.add_class::<structure::Segment>()?;
    m.add_class::<structure::Rod>()?;
    m.add_class::<structure::Current>()?;
    m.add_class::<structure::Sea>()?;
    m.add_class::<waves::Waves>()?;
    m.add_class::<seabed::Seabed>()?;
    m.add_class::<seabed::Bathymetry>()?;
    m.add_class::<seabed::Touchdown>()?;
    m.add_class::<model::Model>()?;
    m.add_class::<state::State>()?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<results::Results>()?;
    m.add_class::<stages::Winch>()?;
    m.add_class::<stages::Stage>()?;
    m.add_class::<stages::Stages>()?;
    m.add_class::<vessel::Vessel>()?;
    m.add_class::<raos::Raos>()?;
    m.add_class::<vessel::PyPid>()?;
    m.add_class::<vessel::PyForce>()?;
    m.add_class::<vessel::PyRoute>()?;
    m.add_class::<vessel::PyTensionControl>()?;
    m.add_class::<lay::Stinger>()?;
    m.add_class::<lay::StingerSection>()?;
    m.add_class::<material::Material>()?;
    m.add_class::<reeling::Straightener>()?;
    m.add_class::<reeling::ReelLay>()?;
    m.add_function(wrap_pyfunction!(reeling::design_straightener, m)?)?;
    m.add_class::<lay::RollerBox>()?;
    m.add_class::<lay::SLay>()?;
    m.add_class::<lay::JLay>()?;
    m.add_class::<station_keeping::Thruster>()?;
    m.add_class::<station_keeping::Allocation>()?;
    m.add_class::<station_keeping::Observer>()?;
    m.add_class::<station_keeping::Wind>()?;
    m.add_class::<station_keeping::HullCoefficients>()?;
    m.add_class::<station_keeping::DriftCoefficients>()?;
    m.add_function(wrap_pyfunction!(capability::dp_capability_wind, m)?)?;
    m.add_function(wrap_pyfunction!(capability::environment_load, m)?)?;
    Ok(())
}
