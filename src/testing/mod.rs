//! proptest strategies for property-based patch tests (feature `proptest-support`).
