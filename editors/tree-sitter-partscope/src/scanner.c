// External scanner of the Partscope grammar: decides what a `;` is.
//
// FANUC and ServoWorks end a block with `;`; RS274/NGC starts a comment with
// it, and ServoWorks manuals put prose after it. The dialect is not known here,
// so the rest of the line decides:
// - nothing but blanks, or another `;`: end of block;
// - G-code that itself ends in `;` (`G01 X1.; G02 X2. R1.;`, several FANUC
//   blocks on one line): end of block, and the rest is parsed as blocks;
// - anything else: a comment to the end of the line.
// The scanner keeps no state.

#include "tree_sitter/parser.h"

#include <stdbool.h>
#include <stdint.h>

enum TokenType { END_OF_BLOCK, LINE_COMMENT };

static bool is_blank(int32_t c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }

static bool is_eol(int32_t c) { return c == '\n' || c == '\r'; }

static bool is_upper(int32_t c) { return c >= 'A' && c <= 'Z'; }

static bool starts_value(int32_t c) {
  return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == '#' || c == '[';
}

static void skip_blanks(TSLexer *lexer) {
  while (is_blank(lexer->lookahead)) lexer->advance(lexer, false);
}

// Macro B statements, which start with a run of letters rather than one address.
static bool is_statement(const char *run, int len) {
  static const char *const words[] = {"IF", "GOTO", "WHILE", "DO", "END", "POPEN", "PCLOS", "DPRNT", "BPRNT"};
  for (unsigned i = 0; i < sizeof(words) / sizeof(words[0]); i++) {
    const char *w = words[i];
    int n = 0;
    while (w[n] && n < len && w[n] == run[n]) n++;
    if (!w[n] && n == len) return true;
  }
  return false;
}

// Reads the start of what follows the `;` (blanks skipped): whether it begins
// like a block (an upper-case address with a value, a parameter, a block
// delete, a comment, a program number or a Macro B statement).
static bool starts_block(TSLexer *lexer) {
  int32_t c = lexer->lookahead;
  if (c == '#' || c == '/' || c == '(' || c == ':' || c == '<') return true;
  if (!is_upper(c)) return false;
  char run[8];
  int len = 0;
  while (is_upper(lexer->lookahead)) {
    if (len < (int)sizeof(run)) run[len] = (char)lexer->lookahead;
    len++;
    lexer->advance(lexer, false);
  }
  if (len == 1) {
    skip_blanks(lexer);
    return starts_value(lexer->lookahead);
  }
  return len <= (int)sizeof(run) && is_statement(run, len);
}

void *tree_sitter_partscope_external_scanner_create(void) { return NULL; }

void tree_sitter_partscope_external_scanner_destroy(void *payload) { (void)payload; }

unsigned tree_sitter_partscope_external_scanner_serialize(void *payload, char *buffer) {
  (void)payload;
  (void)buffer;
  return 0;
}

void tree_sitter_partscope_external_scanner_deserialize(void *payload, const char *buffer, unsigned length) {
  (void)payload;
  (void)buffer;
  (void)length;
}

bool tree_sitter_partscope_external_scanner_scan(void *payload, TSLexer *lexer, const bool *valid_symbols) {
  (void)payload;
  if (!valid_symbols[END_OF_BLOCK] && !valid_symbols[LINE_COMMENT]) return false;
  while (is_blank(lexer->lookahead)) lexer->advance(lexer, true);
  if (lexer->lookahead != ';') return false;
  lexer->advance(lexer, false);
  // The end of block is the `;` alone; what follows is only looked at.
  lexer->mark_end(lexer);
  skip_blanks(lexer);

  bool end_of_block;
  if (lexer->eof(lexer) || is_eol(lexer->lookahead) || lexer->lookahead == ';') {
    end_of_block = true;
  } else {
    bool block = starts_block(lexer);
    int32_t last = 0;
    while (!lexer->eof(lexer) && !is_eol(lexer->lookahead)) {
      if (!is_blank(lexer->lookahead)) last = lexer->lookahead;
      lexer->advance(lexer, false);
    }
    end_of_block = block && last == ';';
  }

  if (end_of_block && valid_symbols[END_OF_BLOCK]) {
    lexer->result_symbol = END_OF_BLOCK;
    return true;
  }
  if (valid_symbols[LINE_COMMENT]) {
    // Runs to the end of the line (where the scan above stopped).
    while (!lexer->eof(lexer) && !is_eol(lexer->lookahead)) lexer->advance(lexer, false);
    lexer->mark_end(lexer);
    lexer->result_symbol = LINE_COMMENT;
    return true;
  }
  if (valid_symbols[END_OF_BLOCK]) {
    lexer->result_symbol = END_OF_BLOCK;
    return true;
  }
  return false;
}
