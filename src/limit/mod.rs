//! The hydrodynamic limit (being written).
