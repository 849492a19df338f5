//! The one error type of the model crate.

/// A configuration the model cannot honour. Every variant names the field
/// (as it is spelled in a scenario file) and says how to fix it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ConfigError {
    /// A field's value is out of range or inconsistent with another field.
    #[error("field `{field}`: {problem}; {fix}")]
    Invalid {
        /// The field as spelled in a scenario file, e.g. `master.clock_khz`.
        field: String,
        /// What is wrong with it.
        problem: String,
        /// What to write instead.
        fix: String,
    },
}

impl ConfigError {
    /// Shorthand for [`ConfigError::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        problem: impl Into<String>,
        fix: impl Into<String>,
    ) -> Self {
        ConfigError::Invalid {
            field: field.into(),
            problem: problem.into(),
            fix: fix.into(),
        }
    }

    /// The field the error is about.
    pub fn field(&self) -> &str {
        match self {
            ConfigError::Invalid { field, .. } => field,
        }
    }
}

/// Result alias of the model crate.
pub type Result<T, E = ConfigError> = std::result::Result<T, E>;
