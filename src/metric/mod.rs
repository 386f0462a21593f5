//! Extrinsic metrics on the configuration space of a 3-RPR (SPEC A.3–A.5): segment and triangle distances, the nine interpretations `PLATFORM/BASE`, and D(K, K′).
