//! Lossless syntax: every byte of the input belongs to exactly one token, and
//! the blocks, words, expressions and statements of the program refer to the
//! text by byte spans.
//!
//! The tree is flat (vectors of tokens, items and expression nodes indexed by
//! `u32`) so that parsing a million-line CAM program makes a handful of
//! allocations, not millions. The parser is resumable ([`Parser::parse_blocks`])
//! so a host can stream a file through the analysis a chunk of blocks at a time.

mod ast;
mod parser;

pub use ast::*;
pub use parser::{
    block_tokens, parse, parse_lean, parse_serial, parse_window, ParseOptions, Parser, ParserState,
    MAX_EXPR_HEIGHT,
};
