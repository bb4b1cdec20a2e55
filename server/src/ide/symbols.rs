//! Document symbols and folding ranges: programs, subprograms, O-word control
//! blocks and tool sections, computed once as nested regions of blocks.

use analyzer::syntax::{ItemKind, OKeyword, OLabel, OWord, Program};
use analyzer::Span;

use super::Analysis;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RegionKind {
    Program,
    Sub,
    Control,
    Tool,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    pub kind: RegionKind,
    pub name: String,
    /// Label key for O-word regions (to match the closing statement).
    label: String,
    /// Whether an O-word `do` opened it (a later `while` closes it).
    is_do: bool,
    pub start_block: usize,
    pub end_block: usize,
    /// What names the region (the head, the `sub` statement, the `M6` block).
    pub selection: Span,
    pub parent: Option<usize>,
}

fn label_text(program: &Program, ow: &OWord) -> String {
    match ow.label {
        OLabel::Number(n) => format!("o{n}"),
        OLabel::Name => format!(
            "o<{}>",
            program.str_of(ow.name_span()).trim().to_ascii_lowercase()
        ),
        _ => "o?".into(),
    }
}

struct Builder {
    regions: Vec<Region>,
    stack: Vec<usize>,
}

impl Builder {
    fn open(&mut self, mut r: Region) {
        r.parent = self.stack.last().copied();
        self.regions.push(r);
        self.stack.push(self.regions.len() - 1);
    }

    fn close_top(&mut self, end: usize) {
        if let Some(i) = self.stack.pop() {
            let r = &mut self.regions[i];
            r.end_block = end.max(r.start_block);
        }
    }

    /// Closes regions down to and including the innermost one `matches`
    /// accepts; does nothing when no open region matches.
    fn close_matching(&mut self, end: usize, matches: impl Fn(&Region) -> bool) -> bool {
        let Some(pos) = self.stack.iter().rposition(|&i| matches(&self.regions[i])) else {
            return false;
        };
        while self.stack.len() > pos + 1 {
            self.close_top(end.saturating_sub(1));
        }
        self.close_top(end);
        true
    }
}

/// The regions of a program, in order of their start (parents before children).
pub fn regions(program: &Program) -> Vec<Region> {
    let mut b = Builder {
        regions: Vec::new(),
        stack: Vec::new(),
    };
    let region = |kind, name: String, label: String, bi: usize, sel: Span| Region {
        kind,
        name,
        label,
        is_do: false,
        start_block: bi,
        end_block: bi,
        selection: sel,
        parent: None,
    };
    for (bi, block) in program.blocks.iter().enumerate() {
        let mut tool: Option<String> = None;
        let mut m6 = false;
        for item in program.items_of(block) {
            match &item.kind {
                ItemKind::ProgramHead { .. } => {
                    while !b.stack.is_empty() {
                        b.close_top(bi.saturating_sub(1));
                    }
                    let text = program.str_of(item.span).trim().to_string();
                    b.open(region(
                        RegionKind::Program,
                        text,
                        String::new(),
                        bi,
                        item.span,
                    ));
                }
                ItemKind::OWord(ow) => {
                    let label = label_text(program, ow);
                    let Some(kw) = ow.keyword else { continue };
                    let name = format!("{label} {}", kw.as_str());
                    match kw {
                        OKeyword::Sub => {
                            b.open(region(RegionKind::Sub, label.clone(), label, bi, item.span))
                        }
                        OKeyword::Endsub => {
                            b.close_matching(bi, |r| r.kind == RegionKind::Sub && r.label == label);
                        }
                        OKeyword::Do | OKeyword::If | OKeyword::Repeat => {
                            let mut r = region(RegionKind::Control, name, label, bi, item.span);
                            r.is_do = kw == OKeyword::Do;
                            b.open(r);
                        }
                        OKeyword::While => {
                            let closes_do = b.close_matching(bi, |r| {
                                r.kind == RegionKind::Control && r.label == label && r.is_do
                            });
                            if !closes_do {
                                b.open(region(RegionKind::Control, name, label, bi, item.span));
                            }
                        }
                        OKeyword::Endwhile | OKeyword::Endif | OKeyword::Endrepeat => {
                            b.close_matching(bi, |r| {
                                r.kind == RegionKind::Control && r.label == label
                            });
                        }
                        _ => {}
                    }
                }
                ItemKind::Word(w) if w.letter == b'T' && !w.comma => {
                    tool = Some(program.str_of(item.span).trim().to_ascii_uppercase());
                }
                ItemKind::Word(w)
                    if w.letter == b'M' && w.num().is_some_and(|n| n.value == 6.0) =>
                {
                    m6 = true
                }
                _ => {}
            }
        }
        if m6 {
            if b.stack
                .last()
                .is_some_and(|&i| b.regions[i].kind == RegionKind::Tool)
            {
                b.close_top(bi.saturating_sub(1));
            }
            let name = match tool {
                Some(t) => format!("{t} M6"),
                None => "M6 tool change".to_string(),
            };
            b.open(region(
                RegionKind::Tool,
                name,
                String::new(),
                bi,
                block.span,
            ));
        }
    }
    let last = program.blocks.len().saturating_sub(1);
    while !b.stack.is_empty() {
        b.close_top(last);
    }
    b.regions
}

fn region_span(program: &Program, r: &Region) -> Span {
    let start = program.blocks[r.start_block].span.start;
    let end = program.blocks[r.end_block].span.end.max(start);
    Span::new(start, end)
}

/// One document symbol: a program, subprogram, O-word block or tool
/// section, with the regions nested in it.
#[derive(Debug, Clone, PartialEq)]
pub struct Symbol {
    pub name: String,
    pub kind: RegionKind,
    /// From the first block's start to the last block's end.
    pub span: Span,
    /// What names it (inside `span`; `span` itself when the head is not).
    pub selection: Span,
    pub children: Vec<Symbol>,
}

impl RegionKind {
    /// The symbol's detail as the outline shows it.
    pub fn detail(self) -> &'static str {
        match self {
            RegionKind::Program => "program",
            RegionKind::Sub => "subprogram",
            RegionKind::Control => "O-word block",
            RegionKind::Tool => "tool",
        }
    }
}

/// The document's symbols, nested.
pub fn document_symbols(program: &Program) -> Vec<Symbol> {
    let regions = regions(program);
    fn build(program: &Program, regions: &[Region], parent: Option<usize>) -> Vec<Symbol> {
        regions
            .iter()
            .enumerate()
            .filter(|(_, r)| r.parent == parent)
            .map(|(i, r)| {
                let span = region_span(program, r);
                let selection = if r.selection.start < span.start || r.selection.end > span.end {
                    span
                } else {
                    r.selection
                };
                Symbol {
                    name: if r.name.is_empty() {
                        "?".into()
                    } else {
                        r.name.clone()
                    },
                    kind: r.kind,
                    span,
                    selection,
                    children: build(program, regions, Some(i)),
                }
            })
            .collect()
    }
    build(program, &regions, None)
}

/// A folding range: whole lines.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fold {
    pub start_line: u32,
    pub end_line: u32,
    /// What a folded region shows.
    pub name: String,
}

/// The regions that span more than one line.
pub fn folding_ranges(a: &Analysis<'_>) -> Vec<Fold> {
    regions(a.program)
        .iter()
        .filter_map(|r| {
            let span = region_span(a.program, r);
            let start_line = a.lines.line_of(span.start as usize) as u32;
            let end_line = a.lines.line_of(span.end as usize) as u32;
            (end_line > start_line).then(|| Fold {
                start_line,
                end_line,
                name: r.name.clone(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use analyzer::syntax::{parse, ParseOptions};
    use analyzer::Dialect;

    fn prog(dialect: Dialect, text: &str) -> Program {
        parse(ParseOptions::new(dialect), text.as_bytes().to_vec())
    }

    #[test]
    fn ngc_subs_loops_and_tools_nest() {
        let text = "o<pocket> sub\no100 while [#1 LT 3]\nG1 X#1\no100 endwhile\no<pocket> endsub\nT1 M6\nG0 X0\nT2 M6\nG0 X1\nM2\n";
        let p = prog(Dialect::Rs274ngc, text);
        let r = regions(&p);
        let summary: Vec<(RegionKind, &str, usize, usize, Option<usize>)> = r
            .iter()
            .map(|r| {
                (
                    r.kind,
                    r.name.as_str(),
                    r.start_block,
                    r.end_block,
                    r.parent,
                )
            })
            .collect();
        assert_eq!(
            summary,
            vec![
                (RegionKind::Sub, "o<pocket>", 0, 4, None),
                (RegionKind::Control, "o100 while", 1, 3, Some(0)),
                (RegionKind::Tool, "T1 M6", 5, 6, None),
                (RegionKind::Tool, "T2 M6", 7, 9, None),
            ]
        );
        let syms = document_symbols(&p);
        assert_eq!(syms.len(), 3);
        assert_eq!(syms[0].children.len(), 1);
    }

    #[test]
    fn fanuc_programs_are_top_level() {
        let text = "%\nO0001;\nT1 M6;\nM98 P1234;\nM30;\nO1234;\nG1 X1.;\nM99;\n%\n";
        let p = prog(Dialect::Fanuc, text);
        let r = regions(&p);
        let names: Vec<(&str, Option<usize>)> =
            r.iter().map(|r| (r.name.as_str(), r.parent)).collect();
        assert_eq!(
            names,
            vec![("O0001", None), ("T1 M6", Some(0)), ("O1234", None)]
        );
        assert!(r[1].end_block < r[2].start_block);
    }
}
