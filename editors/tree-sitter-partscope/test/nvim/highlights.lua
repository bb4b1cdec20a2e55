-- Headless Neovim check of the grammar and its highlight query in a real client:
-- loads parser/partscope.so and queries/partscope/highlights.scm from the
-- runtimepath set up by test/nvim.sh, parses each file of test/highlight and
-- compares the capture Neovim gives each asserted position with the assertion; then
-- edits a buffer and checks the incremental reparse.
-- Works on Neovim 0.7 (Debian's) and later.
local get_query = (vim.treesitter.query and vim.treesitter.query.get) or vim.treesitter.get_query
local failures, checked = 0, 0

local function captures_at(query, tree, buf, row, col)
  -- The capture of the smallest node covering the position: what a highlighter shows.
  local best, best_size
  for id, node in query:iter_captures(tree:root(), buf, row, row + 1) do
    local sr, sc, er, ec = node:range()
    local starts = sr < row or (sr == row and sc <= col)
    local ends = er > row or (er == row and ec > col)
    if starts and ends then
      local size = (er - sr) * 100000 + (ec - sc)
      if not best_size or size <= best_size then
        best, best_size = query.captures[id], size
      end
    end
  end
  return best
end

for _, file in ipairs(vim.fn.glob(vim.env.HIGHLIGHT_DIR .. "/*", false, true)) do
  local lines = vim.fn.readfile(file)
  local buf = vim.api.nvim_create_buf(false, true)
  vim.api.nvim_buf_set_lines(buf, 0, -1, false, lines)
  local parser = vim.treesitter.get_parser(buf, "partscope")
  local tree = parser:parse()[1]
  local query = get_query("partscope", "highlights")
  local code_row
  for i, line in ipairs(lines) do
    local row = i - 1
    local col, name
    local pad, n = line:match("^%(( *)%^ ([%w._]+)%)$")
    if pad then
      col, name = #pad + 1, n
    else
      name = line:match("^%( <%- ([%w._]+)%)$")
      if name then
        col = 0
      end
    end
    if name then
      checked = checked + 1
      local got = captures_at(query, tree, buf, code_row, col)
      if got ~= name then
        failures = failures + 1
        print(string.format("%s:%d:%d: expected %s, Neovim captures %s", file, code_row + 1, col + 1, name, tostring(got)))
      end
    else
      code_row = row
    end
  end
end
-- Incremental reparse: the scanner looks past a `;` to the end of the line, so an edit
-- there must change what the `;` is. `G2` is in a comment until the line ends in `;`.
do
  local buf = vim.api.nvim_create_buf(false, true)
  vim.api.nvim_buf_set_lines(buf, 0, -1, false, { "G1 X1; G2 X2", "G0 Z1" })
  local parser = vim.treesitter.get_parser(buf, "partscope")
  local query = get_query("partscope", "highlights")
  local before = captures_at(query, parser:parse()[1], buf, 0, 7)
  vim.api.nvim_buf_set_text(buf, 0, 12, 0, 12, { ";" })
  local after = captures_at(query, parser:parse()[1], buf, 0, 7)
  checked = checked + 2
  if before ~= "comment" then
    failures = failures + 1
    print("before the edit, G2 after `;` should be a comment, Neovim captures " .. tostring(before))
  end
  if after ~= "keyword" then
    failures = failures + 1
    print("after the edit, G2 should be a G code, Neovim captures " .. tostring(after))
  end
end

print(string.format("nvim highlights: %d passed, %d failed", checked - failures, failures))
vim.cmd(failures == 0 and "qall!" or "cquit!")
