//! The speed-vs-accuracy atlas (being written).
