//! Conversions between Python values (numbers, sequences, numpy arrays) and engine types.
use crate::errors::input;
use nalgebra::{Matrix3, Vector3};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;

/// A float array of any shape from `value`, flattened, with its shape.
pub fn float_array(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let numpy = value.py().import("numpy")?;
    let array = numpy
        .call_method1("asarray", (value, "float64"))
        .map_err(|_| {
            input(
                argument,
                value.repr().map_or("?".into(), |r| r.to_string()),
                "must be numeric",
            )
        })?;
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    let flat: Vec<f64> = array
        .call_method0("ravel")?
        .call_method0("tolist")?
        .extract()?;
    Ok((flat, shape))
}

/// A 3-vector (m, N, N·m ...) from any sequence of three numbers.
pub fn vector3(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<Vector3<f64>> {
    let (flat, shape) = float_array(value, argument)?;
    if shape != [3] {
        return Err(input(
            argument,
            format!("an array of shape {shape:?}"),
            "must have shape (3,)",
        ));
    }
    Ok(Vector3::from_column_slice(&flat))
}

/// A 3×3 matrix (row-major as numpy gives it).
pub fn matrix3(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<Matrix3<f64>> {
    let (flat, shape) = float_array(value, argument)?;
    if shape != [3, 3] {
        return Err(input(
            argument,
            format!("an array of shape {shape:?}"),
            "must have shape (3, 3)",
        ));
    }
    Ok(Matrix3::from_row_slice(&flat))
}

/// All values of an array of any shape, flattened (row-major).
pub fn flat(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<Vec<f64>> {
    Ok(float_array(value, argument)?.0)
}

/// A 6×6 matrix (row-major as numpy gives it).
pub fn float_matrix6(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<nalgebra::Matrix6<f64>> {
    let (flat, shape) = float_array(value, argument)?;
    if shape != [6, 6] {
        return Err(input(
            argument,
            format!("an array of shape {shape:?}"),
            "must have shape (6, 6)",
        ));
    }
    finite_or_error(argument, &flat)?;
    Ok(nalgebra::Matrix6::from_row_slice(&flat))
}

fn finite_or_error(argument: &str, values: &[f64]) -> PyResult<()> {
    pipelay::error::finite(argument, values).map_err(crate::errors::to_py)
}

/// An (n, N) array as n vectors of N numbers; `shape` says the shape wanted, for the error.
fn rows<const N: usize>(
    value: &Bound<'_, PyAny>,
    argument: &str,
    shape_wanted: &str,
) -> PyResult<Vec<nalgebra::SVector<f64, N>>> {
    let (flat, shape) = float_array(value, argument)?;
    if shape.len() != 2 || shape[1] != N {
        return Err(input(
            argument,
            format!("an array of shape {shape:?}"),
            &format!("must have shape {shape_wanted}"),
        ));
    }
    Ok(flat
        .chunks_exact(N)
        .map(nalgebra::SVector::<f64, N>::from_column_slice)
        .collect())
}

/// An (n, 3) array of points.
pub fn points(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<Vec<Vector3<f64>>> {
    rows::<3>(value, argument, "(n + 1, 3)")
}

/// An (n, 2) array of plane points (x, y).
pub fn points2(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<Vec<nalgebra::Vector2<f64>>> {
    rows::<2>(value, argument, "(k, 2): one (x, y) row per point")
}

/// A 1-D float array of any length.
pub fn vector(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<Vec<f64>> {
    let (flat, shape) = float_array(value, argument)?;
    if shape.len() != 1 {
        return Err(input(
            argument,
            format!("an array of shape {shape:?}"),
            "must be one-dimensional",
        ));
    }
    Ok(flat)
}

/// `N` numbers from a scalar (repeated) or a sequence of length `N`.
pub fn scalar_or_array<const N: usize>(
    value: &Bound<'_, PyAny>,
    argument: &str,
) -> PyResult<[f64; N]> {
    let (flat, shape) = float_array(value, argument)?;
    match (shape.as_slice(), flat.len()) {
        ([], 1) => Ok([flat[0]; N]),
        ([n], _) if *n == N => {
            let mut out = [0.0; N];
            out.copy_from_slice(&flat);
            Ok(out)
        }
        _ => Err(input(
            argument,
            format!("an array of shape {shape:?}"),
            &format!("must be a number or a sequence of {N} numbers"),
        )),
    }
}

/// `N` numbers from a sequence of length `N` exactly.
pub fn array<const N: usize>(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<[f64; N]> {
    let (flat, shape) = float_array(value, argument)?;
    if shape != [N] {
        return Err(input(
            argument,
            format!("an array of shape {shape:?}"),
            &format!("must have shape ({N},)"),
        ));
    }
    let mut out = [0.0; N];
    out.copy_from_slice(&flat);
    Ok(out)
}

/// (k, 3) numpy array from 3-vectors.
pub fn points_to_numpy<'py>(py: Python<'py>, points: &[Vector3<f64>]) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<Vec<f64>> = points.iter().map(|p| p.as_slice().to_vec()).collect();
    PyArray2::from_vec2(py, &rows).expect("rows of equal length")
}

/// (k, 3, 3) numpy array from matrices.
pub fn matrices_to_numpy<'py>(
    py: Python<'py>,
    matrices: &[Matrix3<f64>],
) -> Bound<'py, PyArray3<f64>> {
    let data: Vec<Vec<Vec<f64>>> = matrices
        .iter()
        .map(|m| {
            (0..3)
                .map(|i| (0..3).map(|j| m[(i, j)]).collect())
                .collect()
        })
        .collect();
    PyArray3::from_vec3(py, &data).expect("3×3 blocks")
}

/// 1-D numpy array.
pub fn to_numpy<'py>(py: Python<'py>, values: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, values)
}

/// Array of `shape` from flat row-major data.
pub fn shaped<'py>(py: Python<'py>, data: &[f64], shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_slice(py, data)
        .reshape(shape.to_vec())?
        .into_any())
}
