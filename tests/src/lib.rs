//! Conformance suite; the tests live in tests/.
