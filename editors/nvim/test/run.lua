-- Headless check driven by test.sh: opens the sample through require("partscope").setup() and
-- requires published diagnostics, a non-empty hover, a rename across two files and a
-- formatting from the real server; then the cycle-time lens, inlay block times, loop values on
-- hover and formatting of editors/test/loop.ngc, checked against `partscope run`.
local bin = os.getenv("PARTSCOPE_BIN")
local sample = os.getenv("PARTSCOPE_SAMPLE")
local timeout_ms = tonumber(os.getenv("PARTSCOPE_TIMEOUT_MS") or "20000")
local deadline = (vim.uv or vim.loop).now() + timeout_ms

local function finish(ok, msg)
  io.stderr:write((ok and "ok: " or "FAIL: ") .. msg .. "\n")
  io.stderr:flush()
  for _, c in pairs(vim.lsp.get_clients and vim.lsp.get_clients() or vim.lsp.get_active_clients()) do
    vim.lsp.stop_client(c.id)
  end
  vim.wait(500, function()
    return #(vim.lsp.get_clients and vim.lsp.get_clients() or vim.lsp.get_active_clients()) == 0
  end, 20)
  vim.cmd(ok and "qall!" or "cquit 1")
end

local function remaining()
  return math.max(0, deadline - (vim.uv or vim.loop).now())
end

-- The toolpath page is "opened" by copying it here (in one rename, so it is whole once there).
local opened = vim.fn.fnamemodify(sample, ":h") .. "/opened.html"
local ok, err = pcall(function()
  require("partscope").setup({
    cmd = { bin, "lsp" },
    keymaps = { rename = false },
    open_cmd = { "sh", "-c", 'cp "$1" "$0.tmp" && mv "$0.tmp" "$0"', opened },
  })
end)
if not ok then
  finish(false, "setup() raised: " .. tostring(err))
  return
end

vim.cmd("edit " .. vim.fn.fnameescape(sample))
local buf = vim.api.nvim_get_current_buf()
if vim.bo[buf].filetype ~= "gcode" then
  finish(false, "filetype of " .. sample .. " is '" .. vim.bo[buf].filetype .. "', expected 'gcode'")
  return
end

local function attached()
  local list = vim.lsp.get_clients and vim.lsp.get_clients({ bufnr = buf }) or vim.lsp.buf_get_clients(buf)
  for _, c in pairs(list) do
    if c.name == "partscope" then
      return c
    end
  end
  return nil
end

if not vim.wait(remaining(), function()
  local c = attached()
  return c ~= nil and c.initialized
end, 50) then
  finish(false, ("the partscope client did not initialize within %d ms (is '%s lsp' a working LSP server?)"):format(timeout_ms, bin))
  return
end

if not vim.wait(remaining(), function()
  return #vim.diagnostic.get(buf) > 0
end, 50) then
  finish(false, ("no diagnostics arrived within %d ms for %s, which has known errors"):format(timeout_ms, sample))
  return
end
local diags = vim.diagnostic.get(buf)
local first = diags[1]

-- Hover on the G21 of line 2.
local row, col
for i, line in ipairs(vim.api.nvim_buf_get_lines(buf, 0, -1, false)) do
  local s = line:find("G21", 1, true)
  if s then
    row, col = i - 1, s
    break
  end
end
local params = { textDocument = { uri = vim.uri_from_bufnr(buf) }, position = { line = row, character = col } }
local responses, herr = vim.lsp.buf_request_sync(buf, "textDocument/hover", params, math.max(1, remaining()))
if not responses then
  finish(false, "hover request failed: " .. tostring(herr or ("no answer within " .. timeout_ms .. " ms")))
  return
end

local function text_of(contents)
  if type(contents) == "string" then
    return contents
  end
  if type(contents) ~= "table" then
    return ""
  end
  if contents.value ~= nil then
    return tostring(contents.value)
  end
  local parts = {}
  for _, c in ipairs(contents) do
    table.insert(parts, text_of(c))
  end
  return table.concat(parts, "\n")
end

local hover = ""
for _, r in pairs(responses) do
  if r.result and r.result.contents then
    hover = hover .. text_of(r.result.contents)
  end
end
if hover:match("^%s*$") then
  finish(false, ("hover at line %d col %d returned no content (%s)"):format(row + 1, col, vim.inspect(responses)))
  return
end

-- Completion through 'omnifunc', and the mappings asked for (all but rename).
if vim.bo[buf].omnifunc ~= "v:lua.vim.lsp.omnifunc" then
  finish(false, "omnifunc is '" .. vim.bo[buf].omnifunc .. "', expected v:lua.vim.lsp.omnifunc")
  return
end
local gd = vim.fn.maparg("gd", "n", false, true)
if type(gd) ~= "table" or gd.buffer ~= 1 then
  finish(false, "no buffer mapping for gd: " .. vim.inspect(gd))
  return
end
if vim.fn.maparg("<leader>rn", "n") ~= "" then
  finish(false, "<leader>rn is mapped although setup() left rename out")
  return
end

-- :PartscopeToolpath writes the page with `partscope run --html` and hands it to the opener.
if vim.fn.maparg("<leader>pt", "n") == "" then
  finish(false, "no buffer mapping for <leader>pt (toolpath)")
  return
end
vim.cmd("PartscopeToolpath")
if not vim.wait(remaining(), function()
  return vim.fn.filereadable(opened) == 1
end, 50) then
  finish(false, ":PartscopeToolpath opened no page within " .. timeout_ms .. " ms")
  return
end
local page = table.concat(vim.fn.readfile(opened), "\n")
-- The sample's one drawn move: the rapid of line 3 to X0 Y0 Z5.
if not page:find('id="partscope-data"', 1, true) or not page:find('"points":[[0.0,0.0,0.0],[0.0,0.0,5.0]]', 1, true) then
  finish(false, "the opened page lacks the sample's dry run: " .. page:sub(1, 200))
  return
end

-- FANUC `.fnc` and ServoWorks `.sw` files are G-code too, and get the server.
for _, name in ipairs({ "O1000.fnc", "part.sw" }) do
  local path = vim.fn.fnamemodify(sample, ":h") .. "/" .. name
  vim.fn.writefile({ "G00 X1. Y1.;", "M30;" }, path)
  vim.cmd("edit " .. vim.fn.fnameescape(path))
  local b = vim.api.nvim_get_current_buf()
  if vim.bo[b].filetype ~= "gcode" then
    finish(false, name .. " has filetype '" .. vim.bo[b].filetype .. "', expected 'gcode'")
    return
  end
  buf = b
  if not vim.wait(remaining(), function()
    return attached() ~= nil
  end, 50) then
    finish(false, "the partscope client did not attach to " .. name)
    return
  end
end

-- Rename across two files: the call here, the subroutine file's sub/endsub, and its file name.
local dir = vim.fn.fnamemodify(sample, ":h")
vim.fn.writefile({ "o<drill> sub", "G0 X#1", "o<drill> endsub" }, dir .. "/drill.ngc")
vim.fn.writefile({ "o<drill> call [5]", "M2" }, dir .. "/calls.ngc")
vim.cmd("edit " .. vim.fn.fnameescape(dir .. "/calls.ngc"))
buf = vim.api.nvim_get_current_buf()
if not vim.wait(remaining(), function()
  local c = attached()
  return c ~= nil and c.initialized
end, 50) then
  finish(false, "the partscope client did not attach to calls.ngc")
  return
end
local client = attached()
local rparams = { textDocument = { uri = vim.uri_from_bufnr(buf) }, position = { line = 0, character = 3 }, newName = "peck" }
local rres = vim.lsp.buf_request_sync(buf, "textDocument/rename", rparams, math.max(1, remaining()))
local edit
for _, r in pairs(rres or {}) do
  edit = edit or r.result
end
if not edit then
  finish(false, "rename returned no edit: " .. vim.inspect(rres))
  return
end
vim.lsp.util.apply_workspace_edit(edit, client.offset_encoding or "utf-16")
local here_line = vim.api.nvim_buf_get_lines(buf, 0, 1, false)[1]
if here_line ~= "o<peck> call [5]" then
  finish(false, "rename left the call as '" .. tostring(here_line) .. "'")
  return
end
-- The subroutine's buffer: renamed to peck.ngc when the client renames files, else drill.ngc.
local lib = vim.fn.bufnr(dir .. "/peck.ngc")
if lib == -1 then
  lib = vim.fn.bufnr(dir .. "/drill.ngc")
end
local lib_lines = lib ~= -1 and vim.api.nvim_buf_get_lines(lib, 0, -1, false) or {}
if lib_lines[1] ~= "o<peck> sub" or lib_lines[3] ~= "o<peck> endsub" then
  finish(false, "rename did not reach the subroutine file: " .. vim.inspect(lib_lines))
  return
end

-- Formatting with block numbers added: spacing and case normalised, the comment untouched.
vim.fn.writefile({ "g0   x1 (keep  this)", "N5 g1x2  f100", "M2" }, dir .. "/fmt.ngc")
vim.cmd("edit " .. vim.fn.fnameescape(dir .. "/fmt.ngc"))
buf = vim.api.nvim_get_current_buf()
if not vim.wait(remaining(), function()
  local c = attached()
  return c ~= nil and c.initialized
end, 50) then
  finish(false, "the partscope client did not attach to fmt.ngc")
  return
end
local fparams = {
  textDocument = { uri = vim.uri_from_bufnr(buf) },
  options = { tabSize = 4, insertSpaces = true, ["partscope.numbers"] = "add" },
}
local fres = vim.lsp.buf_request_sync(buf, "textDocument/formatting", fparams, math.max(1, remaining()))
local fedits
for _, r in pairs(fres or {}) do
  fedits = fedits or r.result
end
if not fedits then
  finish(false, "formatting returned no edits: " .. vim.inspect(fres))
  return
end
vim.lsp.util.apply_text_edits(fedits, buf, attached().offset_encoding or "utf-16")
local formatted = table.concat(vim.api.nvim_buf_get_lines(buf, 0, -1, false), "\n")
local want = "N10 G0 X1 (keep  this)\nN20 G1 X2 F100\nN30 M2"
if formatted ~= want then
  finish(false, "formatting gave\n" .. formatted .. "\nexpected\n" .. want)
  return
end

-- The dry-run features on editors/test/loop.ngc, against the CLI's figures for the same file.
local loop = os.getenv("PARTSCOPE_LOOP")
local function cli_run(path, ...)
  local out = vim.fn.system(vim.list_extend({ bin, "run", path }, { ... }))
  if vim.v.shell_error ~= 0 then
    error(("`partscope run %s` exited %d: %s"):format(path, vim.v.shell_error, out))
  end
  return vim.fn.json_decode(out)
end
local cli = cli_run(loop, "--format", "json", "--what-if", "off")
local partscope = require("partscope")
vim.cmd("edit " .. vim.fn.fnameescape(loop))
buf = vim.api.nvim_get_current_buf()

-- The plugin asks for the lens after the analysis; nothing else here does.
local function lens_title()
  local l = vim.lsp.codelens.get(buf)[1]
  return l and l.command and l.command.title
end
local want_title = ("Cycle time %s "):format(partscope.format_duration(cli.cycle_time_s))
if not vim.wait(remaining(), function()
  local t = lens_title()
  return t ~= nil and t:sub(1, #want_title) == want_title
end, 50) then
  finish(false, ("the lens never showed '%s…': %s"):format(want_title, tostring(lens_title())))
  return
end

-- (a) Clicking the lens (vim.lsp.codelens.run on its line) shows the server's breakdown.
vim.api.nvim_win_set_cursor(0, { 1, 0 })
vim.lsp.codelens.run()
local shown
if not vim.wait(remaining(), function()
  local b = vim.fn.bufnr("partscope://breakdown")
  shown = b ~= -1 and vim.api.nvim_buf_get_lines(b, 0, -1, false) or nil
  return shown ~= nil and #shown > 1
end, 50) then
  finish(false, "clicking the lens showed no breakdown")
  return
end
local want_first = ("loop.ngc: cycle time %s (%.3f s)"):format(partscope.format_duration(cli.cycle_time_s), cli.cycle_time_s)
if shown[1] ~= want_first or not vim.tbl_contains(shown, "where the time goes") then
  finish(false, ("the breakdown does not start with '%s':\n%s"):format(want_first, table.concat(shown, "\n")))
  return
end
vim.cmd("close")
if vim.api.nvim_get_current_buf() ~= buf then
  vim.cmd("buffer " .. buf)
end

-- An edit is analysed again and the lens follows: one more second of dwell.
local dwell_row
for i, line in ipairs(vim.api.nvim_buf_get_lines(buf, 0, -1, false)) do
  if line == "G4 P0.5" then
    dwell_row = i - 1
  end
end
vim.api.nvim_buf_set_lines(buf, dwell_row, dwell_row + 1, false, { "G4 P1.5" })
local longer = ("Cycle time %s "):format(partscope.format_duration(cli.cycle_time_s + 1))
if not vim.wait(remaining(), function()
  local t = lens_title()
  return t ~= nil and t:sub(1, #longer) == longer
end, 50) then
  finish(false, ("after the edit the lens stayed '%s', expected '%s…'"):format(tostring(lens_title()), longer))
  return
end
vim.api.nvim_buf_set_lines(buf, dwell_row, dwell_row + 1, false, { "G4 P0.5" })
if not vim.wait(remaining(), function()
  local t = lens_title()
  return t ~= nil and t:sub(1, #want_title) == want_title
end, 50) then
  finish(false, "after undoing the edit the lens stayed " .. tostring(lens_title()))
  return
end

-- (b) Inlay block times (Neovim 0.7 has no inlay API: the request itself), each the CLI's
-- time of that line's block.
local function request(method, params)
  local res, e = vim.lsp.buf_request_sync(buf, method, params, math.max(1, remaining()))
  for _, r in pairs(res or {}) do
    if r.result ~= nil then
      return r.result
    end
  end
  error(method .. " gave no result: " .. tostring(e) .. " " .. vim.inspect(res))
end
local uri = vim.uri_from_bufnr(buf)
local nlines = vim.api.nvim_buf_line_count(buf)
local hints = request("textDocument/inlayHint", {
  textDocument = { uri = uri },
  range = { start = { line = 0, character = 0 }, ["end"] = { line = nlines, character = 0 } },
})
local got_hints, want_hints = {}, {}
for _, h in ipairs(hints) do
  local label = type(h.label) == "string" and h.label or h.label[1].value
  table.insert(got_hints, ("%d:%s"):format(h.position.line + 1, label))
end
for _, b in ipairs(cli.blocks) do
  table.insert(want_hints, ("%d:%.3f s"):format(b.line, b.time_s))
end
local want_text = "3:0.142 s 4:1.200 s 8:2.997 s 10:0.500 s 11:0.220 s"
if table.concat(got_hints, " ") ~= table.concat(want_hints, " ") or table.concat(want_hints, " ") ~= want_text then
  finish(false, ("inlay hints %s; the CLI's blocks %s; expected %s"):format(
    table.concat(got_hints, " "), table.concat(want_hints, " "), want_text))
  return
end

-- (c) Hover on #1 in the loop's move: each of the three executions' value.
local loop_row, loop_col
for i, line in ipairs(vim.api.nvim_buf_get_lines(buf, 0, -1, false)) do
  local c = line:find("X[#1", 1, true)
  if c then
    loop_row, loop_col = i - 1, c + 1
  end
end
local hv = request("textDocument/hover", { textDocument = { uri = uri }, position = { line = loop_row, character = loop_col } })
local hover_md = text_of(hv.contents)
local want_values = "Value in the dry run: `3` (last of 3 executions)  \nEach execution: `1`, `2`, `3`"
if not hover_md:find(want_values, 1, true) then
  finish(false, "hover on #1 in the loop lacks its values:\n" .. hover_md)
  return
end

-- (e) Formatting keeps the dry run: the formatted buffer, written beside, runs the same.
local before = vim.api.nvim_buf_get_lines(buf, 0, -1, false)
local edits = request("textDocument/formatting", { textDocument = { uri = uri }, options = { tabSize = 2, insertSpaces = true } })
vim.lsp.util.apply_text_edits(edits, buf, attached().offset_encoding or "utf-16")
local after = vim.api.nvim_buf_get_lines(buf, 0, -1, false)
local want_formatted = {
  "(partscope: dialect=rs274ngc)",
  "G21 G90 G17 G94",
  "G0 X0 Y0 Z5",
  "G1 Z-1 F300",
  "#1 = 0",
  "o100 while [#1 LT 3]",
  "  #1 = [#1 + 1]",
  "  G1 X[#1 * 10] F600",
  "o100 endwhile",
  "G4 P0.5",
  "G0 Z5",
  "M2",
}
if table.concat(after, "\n") ~= table.concat(want_formatted, "\n") then
  finish(false, "formatting gave\n" .. table.concat(after, "\n") .. "\nfrom\n" .. table.concat(before, "\n"))
  return
end
local formatted = vim.fn.fnamemodify(loop, ":h") .. "/loop_formatted.ngc"
vim.fn.writefile(after, formatted)
local cli_after = cli_run(formatted, "--format", "json", "--what-if", "off")
local motions = function(path)
  return #cli_run(path, "--emit", "toolpath").segments
end
local m_before, m_after = motions(loop), motions(formatted)
if cli_after.cycle_time_s ~= cli.cycle_time_s or m_before ~= m_after or m_before ~= 6 then
  finish(false, ("formatting changed the dry run: cycle %s s -> %s s, motions %d -> %d (expected 6)"):format(
    cli.cycle_time_s, cli_after.cycle_time_s, m_before, m_after))
  return
end

finish(
  true,
  ("%d diagnostic(s), first: [%s] %s; hover: %s"):format(
    #diags,
    tostring(first.code or (first.user_data and first.user_data.lsp and first.user_data.lsp.code) or "?"),
    first.message,
    (hover:gsub("%s+", " ")):sub(1, 80)
  )
)
