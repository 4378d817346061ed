//! Closed-form radiometry (filled in by the radiometry issue).
