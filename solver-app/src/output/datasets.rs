//! How the results writer stores a dataset (issue 45): chunked and
//! compressed with HDF5's own shuffle and deflate filters, which every
//! HDF5 reader has (h5py, ParaView's XDMF reader, h5dump) — no plugin
//! filter — and, on the field datasets, attributes that say what they
//! hold: `units`, `components` (column order) and `location` (cell, point
//! or face).
//!
//! HDF5's filters compress on the writer's own thread
//! ([`crate::background_writer`]), while the solver goes on. Shallow
//! ironing, first 30 increments (3,672 cells): 21.2 MB uncompressed;
//! 6.35 MB compressed, 5.2 MB with the writer's smaller chunk B-tree
//! nodes (`ISTORE_K`); the run as fast as uncompressed. Fields may be
//! stored in single precision ([`create_field`], `[output] precision`):
//! the full run (600 increments) 226 MB in double, 131 MB in single.
use std::sync::OnceLock;

use hdf5::plist::dataset_create::Layout;
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Group, H5Type};

use super::Precision;

/// Deflate level: zlib's fast end (levels 1–3; 6 stored the ironing 6 %
/// smaller at twice the cost).
const DEFLATE_LEVEL: u8 = 1;

/// Target bytes of one chunk. The byte shuffle groups a chunk's exponent
/// bytes into planes of an eighth of it: 64 kB chunks stored the ironing
/// 17 % larger than 256 kB ones, 1 MB ones no smaller.
const CHUNK_BYTES: usize = 256 * 1024;

/// Largest dataset (bytes) stored in its object header, uncompressed
/// (HDF5's compact layout): a chunked one costs a chunk B-tree node of
/// about 300 B besides its compressed data, more than the data of a patch
/// of a few faces or of most restart arrays.
const COMPACT_BYTES: usize = 512;

/// Whether the linked libhdf5 has the deflate filter (zlib); without it
/// datasets are written contiguous and uncompressed.
fn deflate_available() -> bool {
    static AVAILABLE: OnceLock<bool> = OnceLock::new();
    *AVAILABLE.get_or_init(hdf5::filters::deflate_available)
}

/// Rows per chunk of a dataset of `shape` with `elem` bytes per value:
/// whole rows, about [`CHUNK_BYTES`] a chunk, in chunks of equal size.
fn chunk_rows(shape: &[usize], elem: usize) -> usize {
    let n = shape[0];
    let row: usize = shape[1..].iter().product::<usize>() * elem;
    let chunks = (n * row).div_ceil(CHUNK_BYTES).max(1);
    n.div_ceil(chunks).max(1)
}

/// Creates dataset `name` in `g` with `data` (row-major, `shape`),
/// chunked and compressed (shuffle, deflate) when the library has deflate
/// and the data is larger than [`COMPACT_BYTES`], in the object header
/// when it is not empty and no larger; a field with its attributes.
pub(super) fn create<T: H5Type>(
    g: &Group,
    name: &str,
    data: &[T],
    shape: &[usize],
) -> hdf5::Result<Dataset> {
    create_at(g, name, data, shape, None)
}

/// [`create`], the attribute `location` (`cell`, `face`) given for a field
/// stored where it does not usually live (the XDMF's copies).
pub(super) fn create_at<T: H5Type>(
    g: &Group,
    name: &str,
    data: &[T],
    shape: &[usize],
    location: Option<&'static str>,
) -> hdf5::Result<Dataset> {
    let builder = g.new_dataset::<T>().shape(shape);
    let ds = if data.is_empty() {
        builder.create(name)?
    } else {
        let ds = if std::mem::size_of_val(data) <= COMPACT_BYTES {
            builder.layout(Layout::Compact).create(name)?
        } else if deflate_available() {
            let mut chunk = shape.to_vec();
            chunk[0] = chunk_rows(shape, std::mem::size_of::<T>());
            builder
                .chunk(chunk)
                .shuffle()
                .deflate(DEFLATE_LEVEL)
                .create(name)?
        } else {
            builder.create(name)?
        };
        ds.write_raw(data)?;
        ds
    };
    if let Some(mut field) = field(name) {
        if let Some(location) = location {
            field.location = location;
        }
        field.write_attributes(&ds)?;
    }
    Ok(ds)
}

/// [`create_at`] for the values of a field, stored in `precision`
/// (single: each value rounded to the nearest `f32`).
pub(super) fn create_field(
    g: &Group,
    name: &str,
    data: &[f64],
    shape: &[usize],
    location: Option<&'static str>,
    precision: Precision,
) -> hdf5::Result<Dataset> {
    match precision {
        Precision::Double => create_at(g, name, data, shape, location),
        Precision::Single => {
            let single: Vec<f32> = data.iter().map(|&x| x as f32).collect();
            create_at(g, name, &single, shape, location)
        }
    }
}

/// What a field dataset holds.
struct Field {
    /// In the case's consistent units.
    units: &'static str,
    /// Column names; empty for a scalar.
    components: &'static [&'static str],
    /// One row per `cell`, `point` or `face`.
    location: &'static str,
}

const XYZ: &[&str] = &["x", "y", "z"];
/// Stress columns, as CASE_FORMAT.md lists them.
const SYMMETRIC: &[&str] = &["xx", "yy", "zz", "xy", "yz", "xz"];
const LENGTH: &str = "length";
const STRESS: &str = "force/length^2";

/// The field a dataset name stands for (the names of CASE_FORMAT.md's
/// results layout and the writer's additions).
fn field(name: &str) -> Option<Field> {
    let (units, components, location) = match name {
        "points" => (LENGTH, XYZ, "point"),
        "displacement" => (LENGTH, XYZ, "cell"),
        "stress" => (STRESS, SYMMETRIC, "cell"),
        "von_mises" => (STRESS, &[][..], "cell"),
        "plastic_strain" => ("1", &[][..], "cell"),
        "face_centres" => (LENGTH, XYZ, "face"),
        "contact_pressure" => (STRESS, &[][..], "face"),
        "contact_traction" => (STRESS, XYZ, "face"),
        "gap" => (LENGTH, &[][..], "face"),
        _ => return None,
    };
    Some(Field {
        units,
        components,
        location,
    })
}

impl Field {
    fn write_attributes(&self, ds: &Dataset) -> hdf5::Result<()> {
        let text = |s: &str| -> hdf5::Result<VarLenUnicode> {
            s.parse()
                .map_err(|_| hdf5::Error::from(format!("'{s}' is no HDF5 string")))
        };
        ds.new_attr::<VarLenUnicode>()
            .create("units")?
            .write_scalar(&text(self.units)?)?;
        ds.new_attr::<VarLenUnicode>()
            .create("location")?
            .write_scalar(&text(self.location)?)?;
        if !self.components.is_empty() {
            let names = self
                .components
                .iter()
                .map(|c| text(c))
                .collect::<hdf5::Result<Vec<_>>>()?;
            ds.new_attr::<VarLenUnicode>()
                .shape([names.len()])
                .create("components")?
                .write_raw(&names)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_are_equal_whole_rows_of_at_most_256_kib() {
        // 3,600 cells × 6 doubles = 172,800 B: one chunk
        assert_eq!(chunk_rows(&[3600, 6], 8), 3600);
        // 100,000 points × 3 doubles: 10 chunks of 10,000 rows (240,000 B)
        assert_eq!(chunk_rows(&[100_000, 3], 8), 10_000);
        assert_eq!(chunk_rows(&[5], 8), 5);
        // a row larger than a chunk: one row
        assert_eq!(chunk_rows(&[4, 100_000], 8), 1);
    }

    /// A dataset of three chunks, the last one partly filled, reads back
    /// bit for bit, and a smooth field is stored in a fraction of its size.
    #[test]
    fn chunked_compressed_datasets_read_back_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let f = hdf5::File::create(dir.path().join("d.h5")).unwrap();
        let n = 25_000;
        let data: Vec<f64> = (0..3 * n).map(|i| (i as f64 * 1e-3).sin()).collect();
        let ds = create(&f, "displacement", &data, &[n, 3]).unwrap();
        assert_eq!(ds.chunk(), Some(vec![8334, 3]));
        assert_eq!(ds.read_raw::<f64>().unwrap(), data);
        let raw = 3 * n as u64 * 8;
        assert!(
            ds.storage_size() < raw * 9 / 10,
            "{} of {raw} B",
            ds.storage_size()
        );
        let ids: Vec<u64> = (0..1000).collect();
        let ds = create(&f, "connectivity", &ids, &[1000]).unwrap();
        assert_eq!(ds.read_raw::<u64>().unwrap(), ids);
        assert!(ds.attr_names().unwrap().is_empty());
        let empty = create::<f64>(&f, "gap", &[], &[0]).unwrap();
        assert_eq!(empty.shape(), [0]);
        assert!(empty.filters().is_empty());
        // 64 values of 8 B: in the object header, as written
        let few: Vec<f64> = (0..64).map(|i| 0.1 * i as f64).collect();
        let ds = create(&f, "contact_pressure", &few, &[64]).unwrap();
        assert_eq!(ds.layout(), Layout::Compact);
        assert_eq!(ds.read_raw::<f64>().unwrap(), few);
        let ds = create(&f, "von_mises", &[few.as_slice(), &[7.0]].concat(), &[65]).unwrap();
        assert_eq!(ds.layout(), Layout::Chunked);
    }

    #[test]
    fn every_field_of_the_layout_has_units_and_a_location() {
        for name in [
            "points",
            "displacement",
            "stress",
            "von_mises",
            "plastic_strain",
            "face_centres",
            "contact_pressure",
            "contact_traction",
            "gap",
        ] {
            let f = field(name).unwrap_or_else(|| panic!("{name}"));
            assert!(!f.units.is_empty() && !f.location.is_empty(), "{name}");
        }
        assert_eq!(field("stress").map(|f| f.components.len()), Some(6));
        assert!(field("connectivity").is_none());
    }
}
