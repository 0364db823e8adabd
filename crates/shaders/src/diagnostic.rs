//! WGSL diagnostics in the compiler-style form `wgsl/<file>:<line>:<col>: error: <message>`,
//! followed by the source line and a caret, mapped back through module composition.

use std::fmt;

use crate::source::{Composed, Location};

/// One error in the WGSL, located in its original file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// Where the error is; `None` when naga gave no span (then the module's first file is named).
    pub location: Option<Location>,
    /// The file named when there is no location.
    pub file: String,
    /// naga's message, with its chain of causes joined by `: `.
    pub message: String,
    /// The label naga attached to the primary span (may be empty).
    pub label: String,
    /// Caret width in characters (at least 1).
    pub width: usize,
    /// Further labelled places (secondary spans), shown as `note:` lines.
    pub notes: Vec<(Location, String)>,
}

/// Every diagnostic of a failed compilation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostic {
    /// Builds a diagnostic from a message and naga's labelled spans (first = primary).
    pub fn from_spans<'a>(
        composed: &Composed,
        message: String,
        spans: impl IntoIterator<Item = (naga::Span, &'a str)>,
    ) -> Self {
        let mut located = spans.into_iter().filter_map(|(span, label)| {
            let range = span.to_range()?;
            let loc = composed.locate(range.start);
            let text = &composed.text[range.clone()];
            let first_line = text.split('\n').next().unwrap_or("");
            Some((loc, label.to_string(), first_line.chars().count().max(1)))
        });
        let primary = located.next();
        let notes = located.map(|(l, s, _)| (l, s)).collect();
        match primary {
            Some((loc, label, width)) => Self {
                file: loc.file.clone(),
                location: Some(loc),
                message,
                label,
                width,
                notes,
            },
            None => Self {
                location: None,
                file: composed.first_file().to_string(),
                message,
                label: String::new(),
                width: 1,
                notes,
            },
        }
    }

    /// A diagnostic for a validation-style error: message with causes, spans from `WithSpan`.
    pub fn from_with_span<E: std::error::Error>(
        composed: &Composed,
        err: &naga::WithSpan<E>,
    ) -> Self {
        let mut message = err.as_inner().to_string();
        let mut cause = err.as_inner().source();
        while let Some(c) = cause {
            message.push_str(": ");
            message.push_str(&c.to_string());
            cause = c.source();
        }
        Self::from_spans(
            composed,
            message,
            err.spans().map(|(s, l)| (*s, l.as_str())),
        )
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Some(loc) = &self.location else {
            return write!(f, "{}: error: {}", self.file, self.message);
        };
        writeln!(f, "{loc}: error: {}", self.message)?;
        let gutter = loc.line.to_string().len();
        writeln!(f, "{:gutter$} |", "")?;
        writeln!(f, "{} | {}", loc.line, loc.line_text)?;
        let pad: String = loc
            .line_text
            .chars()
            .take(loc.col as usize - 1)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        write!(f, "{:gutter$} | {pad}{}", "", "^".repeat(self.width))?;
        if !self.label.is_empty() {
            write!(f, " {}", self.label)?;
        }
        for (l, text) in &self.notes {
            write!(f, "\n{l}: note: {text}")?;
        }
        Ok(())
    }
}

impl fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostics {}
