//! Scene errors: every problem found in a scene, each with its origin, position and field path.

use std::fmt;

/// A 1-based position in a source file (the column counts characters, not bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Location {
    /// Line, starting at 1.
    pub line: usize,
    /// Column in characters, starting at 1.
    pub column: usize,
}

impl Location {
    /// The location of byte `offset` in `src` (clamped to the end of `src`).
    pub fn from_offset(src: &str, offset: usize) -> Self {
        let mut offset = offset.min(src.len());
        while !src.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &src[..offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Self {
            line: before.matches('\n').count() + 1,
            column: before[line_start..].chars().count() + 1,
        }
    }
}

/// What kind of problem a [`Problem`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ProblemKind {
    /// The file could not be read.
    Io,
    /// The TOML is malformed.
    Syntax,
    /// A key that the scene format does not have.
    UnknownField,
    /// A value of the wrong type (a string where a number belongs, a negative count, ...).
    WrongType,
    /// A value of the right type that breaks a validation rule.
    InvalidValue,
    /// `base = "..."` or [`Scene::preset`](crate::Scene::preset) names no preset.
    UnknownPreset,
}

/// One problem found in a scene.
///
/// Displays as `<origin>:<line>:<column>: <message>`, leaving out what is unknown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    /// Where the scene came from (a file path, `<preset NAME>`), if known.
    pub origin: Option<String>,
    /// Position in the source, if the problem can be pinned to one.
    pub location: Option<Location>,
    /// The kind of problem.
    pub kind: ProblemKind,
    /// Dotted field path (`clouds.coverage`), if the problem concerns a field.
    pub path: Option<String>,
    /// The description, e.g. `clouds.coverage = 1.7: must be within [0, 1]`.
    pub message: String,
}

impl Problem {
    pub(crate) fn new(kind: ProblemKind, path: Option<String>, message: String) -> Self {
        Self {
            origin: None,
            location: None,
            kind,
            path,
            message,
        }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(origin) = &self.origin {
            write!(f, "{origin}:")?;
        }
        if let Some(loc) = self.location {
            write!(f, "{}:{}:", loc.line, loc.column)?;
        }
        if self.origin.is_some() || self.location.is_some() {
            f.write_str(" ")?;
        }
        f.write_str(&self.message)
    }
}

/// Everything wrong with a scene, all reported at once.
///
/// Displays as one line per problem, ordered by position in the source.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    problems: Vec<Problem>,
}

impl SceneError {
    /// Wraps a non-empty list of problems.
    pub(crate) fn new(problems: Vec<Problem>) -> Self {
        debug_assert!(!problems.is_empty());
        Self { problems }
    }

    /// The problems, ordered by position in the source (problems without a position last).
    pub fn problems(&self) -> &[Problem] {
        &self.problems
    }

    /// Consumes the error, returning its problems.
    pub fn into_problems(self) -> Vec<Problem> {
        self.problems
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, problem) in self.problems.iter().enumerate() {
            if i > 0 {
                f.write_str("\n")?;
            }
            problem.fmt(f)?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneError {}
