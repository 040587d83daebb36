//! Doubles in a shard's file, as their bit patterns (`u64`), so that a
//! merged report is built from exactly the numbers its shards computed
//! (JSON numbers do not carry NaN or infinities, and their decimal reading
//! is not promised to round-trip). For `#[serde(with = "…")]`.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One `f64`.
pub mod one {
    use super::*;

    /// Writes the bits.
    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        v.to_bits().serialize(s)
    }

    /// Reads the bits.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        u64::deserialize(d).map(f64::from_bits)
    }
}

/// An `Option<f64>`.
pub mod maybe {
    use super::*;

    /// Writes the bits, or `null`.
    pub fn serialize<S: Serializer>(v: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        v.map(f64::to_bits).serialize(s)
    }

    /// Reads the bits, or `null`.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        Option::<u64>::deserialize(d).map(|v| v.map(f64::from_bits))
    }
}

/// A `Vec<f64>`.
pub mod many {
    use super::*;

    /// Writes the bits.
    pub fn serialize<S: Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
        let bits: Vec<u64> = v.iter().map(|x| x.to_bits()).collect();
        bits.serialize(s)
    }

    /// Reads the bits.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        Vec::<u64>::deserialize(d).map(|v| v.into_iter().map(f64::from_bits).collect())
    }
}

#[cfg(test)]
mod tests {
    use serde::{Deserialize, Serialize};

    #[derive(Debug, Serialize, Deserialize)]
    struct Both {
        #[serde(with = "super::one")]
        x: f64,
        #[serde(with = "super::many")]
        xs: Vec<f64>,
        #[serde(with = "super::maybe")]
        some: Option<f64>,
        #[serde(with = "super::maybe")]
        none: Option<f64>,
    }

    #[test]
    fn every_double_comes_back_bit_for_bit() {
        let xs = vec![
            f64::NAN,
            f64::INFINITY,
            -0.0,
            0.1 + 0.2,
            f64::MIN_POSITIVE / 3.0,
        ];
        let text = serde_json::to_string(&Both {
            x: -0.0,
            xs: xs.clone(),
            some: Some(f64::NAN),
            none: None,
        })
        .unwrap();
        let back: Both = serde_json::from_str(&text).unwrap();
        assert_eq!(back.x.to_bits(), (-0.0f64).to_bits());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.xs), bits(&xs));
        assert_eq!(back.some.map(f64::to_bits), Some(f64::NAN.to_bits()));
        assert_eq!(back.none, None);
    }
}
