-- Headless check driven by test.sh: opens the sample through require("partscope").setup() and
-- requires published diagnostics, a non-empty hover, a rename across two files and a
-- formatting from the real server.
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

finish(
  true,
  ("%d diagnostic(s), first: [%s] %s; hover: %s"):format(
    #diags,
    tostring(first.code or (first.user_data and first.user_data.lsp and first.user_data.lsp.code) or "?"),
    first.message,
    (hover:gsub("%s+", " ")):sub(1, 80)
  )
)
