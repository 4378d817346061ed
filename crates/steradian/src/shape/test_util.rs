//! Shared checks for the shape tests.
