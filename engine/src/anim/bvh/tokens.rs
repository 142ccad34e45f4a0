use std::path::Path;

use super::BvhError;

/// The whitespace-separated words of a BVH text, with their line numbers.
pub(super) struct Tokens<'a> {
    path: &'a Path,
    words: std::iter::Peekable<Box<dyn Iterator<Item = (usize, &'a str)> + 'a>>,
    line: usize,
}

impl<'a> Tokens<'a> {
    /// The words of `text`; `path` names it in errors.
    pub fn new(text: &'a str, path: &'a Path) -> Tokens<'a> {
        let words: Box<dyn Iterator<Item = (usize, &'a str)> + 'a> = Box::new(
            text.lines()
                .enumerate()
                .flat_map(|(k, line)| line.split_whitespace().map(move |w| (k + 1, w))),
        );
        Tokens {
            path,
            words: words.peekable(),
            line: 1,
        }
    }

    /// The file, for errors.
    pub fn path(&self) -> &'a Path {
        self.path
    }

    /// The line of the last word taken.
    pub fn line(&self) -> usize {
        self.line
    }

    /// The next word; a syntax error naming `expected` at the end of the file.
    pub fn next(&mut self, expected: &str) -> Result<&'a str, BvhError> {
        match self.words.next() {
            Some((line, word)) => {
                self.line = line;
                Ok(word)
            }
            None => Err(self.syntax(expected, "end of file")),
        }
    }

    /// The next word, which must be `word` (compared ignoring case).
    pub fn expect(&mut self, word: &str) -> Result<(), BvhError> {
        let found = self.next(word)?;
        if found.eq_ignore_ascii_case(word) {
            Ok(())
        } else {
            Err(self.syntax(word, found))
        }
    }

    /// The next word as a finite number; `what` names it in errors.
    pub fn number(&mut self, what: &str) -> Result<f32, BvhError> {
        let word = self.next(what)?;
        let value: f32 = word.parse().map_err(|_| self.syntax(what, word))?;
        if value.is_finite() {
            Ok(value)
        } else {
            Err(BvhError::NonFinite {
                path: self.path.to_path_buf(),
                line: self.line,
                what: format!("{what} is {word}, not a finite number"),
            })
        }
    }

    /// The next word as a count no larger than `limit`.
    pub fn count(&mut self, what: &str, limit: usize) -> Result<usize, BvhError> {
        let word = self.next(what)?;
        let value: usize = word.parse().map_err(|_| self.syntax(what, word))?;
        if value > limit {
            return Err(BvhError::Limit {
                path: self.path.to_path_buf(),
                line: self.line,
                what: format!("{what} {value}"),
                limit,
            });
        }
        Ok(value)
    }

    /// Whether the next word is `word` (ignoring case), without taking it.
    pub fn peek_is(&mut self, word: &str) -> bool {
        self.words
            .peek()
            .is_some_and(|(_, w)| w.eq_ignore_ascii_case(word))
    }

    /// A syntax error at the current line.
    pub fn syntax(&self, expected: &str, found: &str) -> BvhError {
        BvhError::Syntax {
            path: self.path.to_path_buf(),
            line: self.line,
            expected: expected.to_string(),
            found: found.to_string(),
        }
    }
}
