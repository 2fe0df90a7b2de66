//! naga's diagnostics, pointed into the user's own file. The wrapped
//! source is the user's text first (a `#version` line blanked, same length)
//! and the wrapper after it, so a span inside the user's text has the
//! user's line and column; a span past it lies in the wrapper and is said
//! to be so.

use crate::error::GpuError;
use naga::Span;

/// The wrapped source of one kernel and where the user's part ends.
pub(crate) struct Wrapped<'a> {
    /// The shader's file name, as messages name it.
    pub name: &'a str,
    /// The whole source naga parsed.
    pub source: &'a str,
    /// The length of the user's part at its start.
    pub user_len: usize,
}

impl<'a> Wrapped<'a> {
    /// The source `source` of the file `name`, the user's part its first
    /// `user_len` bytes.
    pub(crate) fn new(name: &'a str, source: &'a str, user_len: usize) -> Wrapped<'a> {
        Wrapped {
            name,
            source,
            user_len,
        }
    }

    /// The first line of a diagnostic: `file:line:column: error: message`
    /// for a span in the user's code, or a note that the error lies in the
    /// harness's wrapper (a name the wrapper uses, a function of the
    /// convention with another meaning).
    fn headline(&self, span: Option<Span>, message: &str) -> String {
        let span = span.filter(|s| s.is_defined());
        match span.and_then(|s| s.to_range()) {
            Some(range) if range.start < self.user_len => {
                let at = span.expect("defined").location(self.source);
                format!(
                    "{}:{}:{}: error: {message}",
                    self.name, at.line_number, at.line_position
                )
            }
            Some(_) => format!(
                "{}: error: {message} (in the harness's wrapper after the shader: does the \
                 shader declare a name starting with `harness_`, or a convention's function \
                 with another meaning? see docs/shaders.md)",
                self.name
            ),
            None => format!("{}: error: {message}", self.name),
        }
    }

    fn error(&self, span: Option<Span>, message: &str, rendered: String) -> GpuError {
        GpuError::Shader {
            diagnostic: format!("{}\n{}", self.headline(span, message), rendered.trim_end()),
        }
    }

    /// A WGSL parse error.
    pub(crate) fn wgsl(&self, error: &naga::front::wgsl::ParseError) -> GpuError {
        let span = error.labels().next().map(|(span, _)| span);
        self.error(
            span,
            error.message(),
            error.emit_to_string_with_path(self.source, self.name),
        )
    }

    /// GLSL parse errors (the first one heads the message).
    pub(crate) fn glsl(&self, errors: &naga::front::glsl::ParseErrors) -> GpuError {
        let first = errors.errors.first();
        let message = first.map_or_else(|| "the GLSL does not parse".into(), |e| e.to_string());
        self.error(
            first.map(|e| e.meta),
            &message,
            errors.emit_to_string_with_path(self.source, self.name),
        )
    }

    /// A validation error of the wrapped module.
    pub(crate) fn validation(
        &self,
        error: &naga::WithSpan<naga::valid::ValidationError>,
    ) -> GpuError {
        let span = error.spans().next().map(|(span, _)| *span);
        let mut message = error.as_inner().to_string();
        let mut source = std::error::Error::source(error.as_inner());
        while let Some(cause) = source {
            message.push_str(&format!(": {cause}"));
            source = cause.source();
        }
        self.error(
            span,
            &message,
            error.emit_to_string_with_path(self.source, self.name),
        )
    }
}
