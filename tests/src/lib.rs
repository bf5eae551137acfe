//! The integration suites, `tests/tests/*.rs`: each is a test target of
//! this package, built on the `harness` crate (`xtask/harness`) and the
//! crates it checks. Cargo wants a library or a binary in every package;
//! this one holds nothing else, since every suite's code is its own.
