//! The report's content: claims, each a table of checks, and a gallery;
//! rendered as Markdown.

use std::fmt::Write as _;

/// One measured figure and its verdict against the tests' threshold.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// What is measured (e.g. `mean tilt at +20°`).
    pub quantity: String,
    /// The measured figure(s), formatted with units.
    pub measured: String,
    /// The pass condition, as the tests state it.
    pub threshold: String,
    /// Whether the measurement meets the threshold.
    pub pass: bool,
}

impl Check {
    /// A check from its parts.
    pub fn new(
        quantity: impl Into<String>,
        measured: impl Into<String>,
        threshold: impl Into<String>,
        pass: bool,
    ) -> Check {
        Check {
            quantity: quantity.into(),
            measured: measured.into(),
            threshold: threshold.into(),
            pass,
        }
    }
}

/// A claim of the paper and how our implementation measures against it.
#[derive(Debug, Clone, PartialEq)]
pub struct Claim {
    /// Short title (a Markdown heading).
    pub title: String,
    /// The paper's statement (or the design's, where the paper is qualitative).
    pub statement: String,
    /// How it was measured: scenes, durations, windows.
    pub method: String,
    /// The measured figures.
    pub checks: Vec<Check>,
}

impl Claim {
    /// True when every check passes.
    pub fn passes(&self) -> bool {
        self.checks.iter().all(|c| c.pass)
    }
}

/// One rendered frame of the gallery.
#[derive(Debug, Clone, PartialEq)]
pub struct GalleryImage {
    /// File name stem (`docs/gallery/<name>.png`).
    pub name: String,
    /// What the frame shows.
    pub caption: String,
}

/// The whole report: claims grouped in sections, then the gallery.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// `(section title, claims)` in order.
    pub sections: Vec<(String, Vec<Claim>)>,
    /// Rendered frames, linked as `gallery/<name>.png`.
    pub gallery: Vec<GalleryImage>,
    /// How the report was produced (command, duration mode, machine note).
    pub provenance: String,
}

impl Report {
    /// Number of claims and of those that pass.
    pub fn tally(&self) -> (usize, usize) {
        let claims = self.sections.iter().flat_map(|(_, c)| c);
        claims.fold((0, 0), |(n, ok), c| (n + 1, ok + usize::from(c.passes())))
    }

    /// The report as Markdown: a summary, one table per claim, the gallery.
    pub fn to_markdown(&self) -> String {
        let mut md = String::new();
        let (n, ok) = self.tally();
        md.push_str("# Paper results\n\n");
        let _ = writeln!(md, "{}\n", self.provenance);
        let _ = writeln!(md, "**{ok} of {n} claims pass.**\n");
        md.push_str("| section | claim | verdict |\n|---|---|---|\n");
        for (section, claims) in &self.sections {
            for c in claims {
                let _ = writeln!(md, "| {section} | {} | {} |", c.title, verdict(c.passes()));
            }
        }
        for (section, claims) in &self.sections {
            let _ = writeln!(md, "\n## {section}\n");
            for c in claims {
                let _ = writeln!(md, "### {}\n", c.title);
                let _ = writeln!(md, "> {}\n", c.statement);
                let _ = writeln!(md, "{}\n", c.method);
                md.push_str("| quantity | measured | threshold | verdict |\n|---|---|---|---|\n");
                for k in &c.checks {
                    let _ = writeln!(
                        md,
                        "| {} | {} | {} | {} |",
                        cell(&k.quantity),
                        cell(&k.measured),
                        cell(&k.threshold),
                        verdict(k.pass)
                    );
                }
                md.push('\n');
            }
        }
        if !self.gallery.is_empty() {
            md.push_str("\n## Gallery\n\n");
            for g in &self.gallery {
                let _ = writeln!(
                    md,
                    "**{}** — {}\n\n![{}](gallery/{}.png)\n",
                    g.name, g.caption, g.name, g.name
                );
            }
        }
        md
    }
}

fn verdict(pass: bool) -> &'static str {
    if pass { "pass" } else { "**FAIL**" }
}

/// Text safe inside a Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_has_summary_tables_and_gallery_links() {
        let claim = Claim {
            title: "depth order".into(),
            statement: "soil < sand".into(),
            method: "two walks".into(),
            checks: vec![
                Check::new("order", "1 | 2", "a < b", true),
                Check::new("sharp", "3", "> 4", false),
            ],
        };
        let report = Report {
            sections: vec![("Ground".into(), vec![claim])],
            gallery: vec![GalleryImage {
                name: "sand".into(),
                caption: "prints".into(),
            }],
            provenance: "made by a test".into(),
        };
        assert_eq!(report.tally(), (1, 0));
        let md = report.to_markdown();
        assert!(md.contains("**0 of 1 claims pass.**"));
        assert!(md.contains("| Ground | depth order | **FAIL** |"));
        assert!(md.contains("| order | 1 \\| 2 | a < b | pass |"));
        assert!(md.contains("![sand](gallery/sand.png)"));
    }
}
