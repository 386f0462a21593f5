//! Serde types of every input and output file, and the CSV / JSON / SVG writers.
