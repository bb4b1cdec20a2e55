-- Neovim client for the Partscope G-code language server (`partscope lsp`).
--
-- Works on Neovim 0.7 (vim.lsp.start_client + vim.lsp.buf_attach_client) and on current
-- releases (vim.lsp.start, which also reuses a running client per root directory).
--
--   require("partscope").setup({ dialect = "fanuc" })
local M = {}

M.defaults = {
  -- Command that starts the server; `cmd[1]` may be a path.
  cmd = { "partscope", "lsp" },
  -- File extensions opened as G-code (filetype "gcode"). `sw` takes the extension from
  -- Neovim's own `sway` filetype; drop it and list CNC folders in `patterns` if you edit Sway.
  extensions = { "nc", "ngc", "tap", "cnc", "gcode", "eia", "dat", "min", "mpf", "fnc", "sw" },
  -- More autocommand patterns opened as G-code, e.g. { "*/cnc/*.sw" }.
  patterns = {},
  filetypes = { "gcode" },
  -- Files or directories whose presence marks the project root (searched upwards).
  root_markers = { "partscope.toml", ".partscope.toml", ".git" },
  -- initializationOptions and the `partscope` section of workspace/configuration.
  dialect = nil, -- "servoworks" | "rs274ngc" | "fanuc" | nil (decide per file)
  machine = nil, -- path of a machine profile, or nil
  select = {},
  ignore = {},
  -- Passed through to the LSP client.
  on_attach = nil,
  capabilities = nil,
  handlers = nil,
  -- Define :PartscopeDryRun, :PartscopeBreakdown, :PartscopeToolpath, :PartscopeRule and
  -- :PartscopeRestart.
  commands = true,
  -- :PartscopeToolpath writes `partscope run FILE --html PAGE` to a temporary file and opens
  -- it with this command (the page's path is appended): nil picks the system opener
  -- (xdg-open, open on macOS, start on Windows).
  open_cmd = nil,
  -- Set 'omnifunc' to the LSP completion (<C-x><C-o>) in attached buffers.
  omnifunc = true,
  -- Show the cycle-time code lens above the first line, refreshed after each analysis.
  codelens = true,
  -- Buffer-local mappings: false (none), true (the defaults below) or a table of
  -- { action = lhs } overriding them (an lhs of false leaves that action unmapped).
  keymaps = false,
}

M.default_keymaps = {
  hover = "K",
  definition = "gd",
  references = "gr",
  code_action = "<leader>ca",
  rename = "<leader>rn",
  lens = "<leader>pl",
  dry_run = "<leader>pd",
  toolpath = "<leader>pt",
  rule = "<leader>pr",
}

local config = nil
-- Client ids by root directory, for Neovim versions without vim.lsp.start.
local clients_by_root = {}
local warned_missing = false

local function notify(msg, level)
  vim.notify("partscope: " .. msg, level or vim.log.levels.INFO)
end

local function json_value(v)
  if v == nil then
    return vim.NIL
  end
  return v
end

local function server_settings()
  local machine = config.machine
  if machine ~= nil then
    machine = vim.fn.fnamemodify(vim.fn.expand(machine), ":p")
  end
  return {
    dialect = json_value(config.dialect),
    machine = json_value(machine),
    select = config.select or {},
    ignore = config.ignore or {},
  }
end

local function find_root(path)
  local dir = path ~= "" and vim.fn.fnamemodify(path, ":p:h") or vim.fn.getcwd()
  for _, marker in ipairs(config.root_markers) do
    local found = vim.fn.findfile(marker, dir .. ";")
    if found == "" then
      found = vim.fn.finddir(marker, dir .. ";")
    end
    if found ~= "" then
      -- The marker's parent directory; strip a trailing slash that finddir results carry.
      local full = vim.fn.fnamemodify(found, ":p"):gsub("/$", "")
      return vim.fn.fnamemodify(full, ":h")
    end
  end
  return dir
end

local actions = {
  hover = function()
    vim.lsp.buf.hover()
  end,
  definition = function()
    vim.lsp.buf.definition()
  end,
  references = function()
    vim.lsp.buf.references()
  end,
  code_action = function()
    vim.lsp.buf.code_action()
  end,
  rename = function()
    vim.lsp.buf.rename()
  end,
  lens = function()
    vim.lsp.codelens.run()
  end,
  dry_run = function()
    vim.cmd("PartscopeDryRun")
  end,
  toolpath = function()
    vim.cmd("PartscopeToolpath")
  end,
  rule = function()
    vim.cmd("PartscopeRule")
  end,
}

--- The buffer mappings `setup({ keymaps = … })` asks for: { action = lhs }.
function M.keymaps_for(option)
  if not option then
    return {}
  end
  local maps = vim.deepcopy(M.default_keymaps)
  if type(option) == "table" then
    for action, lhs in pairs(option) do
      maps[action] = lhs
    end
  end
  for action, lhs in pairs(maps) do
    if not lhs or actions[action] == nil then
      maps[action] = nil
    end
  end
  return maps
end

-- Per buffer: completion through 'omnifunc' and the optional mappings.
local function on_attach(client, bufnr)
  if config.omnifunc then
    vim.bo[bufnr].omnifunc = "v:lua.vim.lsp.omnifunc"
  end
  if config.codelens then
    M.refresh_lenses(bufnr)
  end
  for action, lhs in pairs(M.keymaps_for(config.keymaps)) do
    vim.keymap.set("n", lhs, actions[action], { buffer = bufnr, desc = "Partscope: " .. (action:gsub("_", " ")) })
  end
  if config.on_attach then
    config.on_attach(client, bufnr)
  end
end

-- Buffers whose lenses are out of date but were not current when their analysis arrived
-- (Neovim 0.7's vim.lsp.codelens.refresh() works on the current buffer only).
local stale_lenses = {}

--- Asks for `bufnr`'s code lenses now if it is the current buffer, else when it is entered.
function M.refresh_lenses(bufnr)
  if not config.codelens or not vim.api.nvim_buf_is_loaded(bufnr) then
    return
  end
  if bufnr == vim.api.nvim_get_current_buf() then
    stale_lenses[bufnr] = nil
    vim.lsp.codelens.refresh()
  else
    stale_lenses[bufnr] = true
  end
end

-- The buffer attached to a partscope client whose URI is `uri`, if any.
local function buffer_of(uri)
  for _, b in ipairs(vim.api.nvim_list_bufs()) do
    if vim.api.nvim_buf_is_loaded(b) and vim.uri_from_bufnr(b) == uri then
      return b
    end
  end
  return nil
end

-- Each publish follows an analysis (the second one of a large file includes the dry run),
-- so it is when the cycle time in the lens may have changed.
local function publish_handler(user)
  return function(err, result, ctx, cfg)
    local base = user or vim.lsp.handlers["textDocument/publishDiagnostics"]
    base(err, result, ctx, cfg)
    local b = result and result.uri and buffer_of(result.uri)
    if b then
      M.refresh_lenses(b)
    end
  end
end

local function client_config(root)
  local settings = server_settings()
  local handlers = vim.tbl_extend("force", {}, config.handlers or {})
  handlers["textDocument/publishDiagnostics"] = publish_handler(handlers["textDocument/publishDiagnostics"])
  return {
    name = "partscope",
    cmd = config.cmd,
    root_dir = root,
    workspace_folders = { { uri = vim.uri_from_fname(root), name = root } },
    init_options = settings,
    settings = { partscope = settings },
    on_attach = on_attach,
    capabilities = config.capabilities,
    handlers = handlers,
  }
end

local function server_available()
  local exe = config.cmd[1]
  if vim.fn.executable(exe) == 1 then
    return true
  end
  if not warned_missing then
    warned_missing = true
    notify(
      ("cannot run %q; install partscope or pass setup({ cmd = { '/path/to/partscope', 'lsp' } })"):format(exe),
      vim.log.levels.ERROR
    )
  end
  return false
end

--- Starts (or reuses) the server for `bufnr` and attaches the buffer. Returns the client id.
function M.attach(bufnr)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  if config == nil then
    M.setup({})
  end
  if not server_available() then
    return nil
  end
  local root = find_root(vim.api.nvim_buf_get_name(bufnr))
  -- vim.lsp.start honours opts.bufnr from 0.9 on; 0.8's always attaches the current buffer.
  if vim.lsp.start and (vim.fn.has("nvim-0.9") == 1 or bufnr == vim.api.nvim_get_current_buf()) then
    return vim.lsp.start(client_config(root), { bufnr = bufnr })
  end
  local id = clients_by_root[root]
  local client = id and vim.lsp.get_client_by_id(id)
  if client == nil or (client.is_stopped and client.is_stopped()) then
    id = vim.lsp.start_client(client_config(root))
    clients_by_root[root] = id
  end
  if id then
    vim.lsp.buf_attach_client(bufnr, id)
  end
  return id
end

local function partscope_clients(bufnr)
  local out = {}
  local all
  if vim.lsp.get_clients then
    all = vim.lsp.get_clients({ bufnr = bufnr })
  else
    all = vim.lsp.buf_get_clients(bufnr)
  end
  for _, c in pairs(all) do
    if c.name == "partscope" then
      table.insert(out, c)
    end
  end
  return out
end

local function scratch(lines, name)
  vim.cmd("botright new")
  local buf = vim.api.nvim_get_current_buf()
  vim.api.nvim_buf_set_lines(buf, 0, -1, false, lines)
  vim.bo[buf].buftype = "nofile"
  vim.bo[buf].bufhidden = "wipe"
  vim.bo[buf].modifiable = false
  vim.bo[buf].filetype = "markdown"
  pcall(vim.api.nvim_buf_set_name, buf, name)
end

--- `h:mm:ss` above an hour, `m:ss.s` below.
function M.format_duration(s)
  if type(s) ~= "number" then
    return "-"
  end
  local a = math.abs(s)
  local text
  if a < 3599.95 then
    local tenths = math.floor(a * 10 + 0.5)
    local m = math.floor(tenths / 600)
    text = ("%d:%04.1f"):format(m, (tenths - m * 600) / 10)
  else
    local whole = math.floor(a + 0.5)
    text = ("%d:%02d:%02d"):format(math.floor(whole / 3600), math.floor((whole % 3600) / 60), whole % 60)
  end
  return (s < 0 and "-" or "") .. text
end

--- Asks the server for the dry-run result of `bufnr`; `callback(err, result)`.
function M.dry_run(bufnr, callback)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local client = partscope_clients(bufnr)[1]
  if client == nil then
    callback("no partscope client attached to this buffer", nil)
    return
  end
  local params = { textDocument = { uri = vim.uri_from_bufnr(bufnr) } }
  local handler = function(err, result)
    if err then
      callback(err.message or vim.inspect(err), nil)
    else
      callback(nil, result)
    end
  end
  -- Client methods take `self` from 0.11 on; the field-call form is deprecated there.
  if vim.fn.has("nvim-0.11") == 1 then
    client:request("partscope/dryRun", params, handler, bufnr)
  else
    client.request("partscope/dryRun", params, handler, bufnr)
  end
end

local function show_dry_run()
  local bufnr = vim.api.nvim_get_current_buf()
  M.dry_run(bufnr, function(err, r)
    if err then
      notify("dry run failed: " .. err, vim.log.levels.ERROR)
      return
    end
    local f = M.format_duration
    local segs = (r.toolpath and r.toolpath.segments) or {}
    local lines = {
      "# Dry run: " .. vim.fn.fnamemodify(vim.api.nvim_buf_get_name(bufnr), ":t"),
      "",
      ("cycle time     %12s"):format(f(r.cycle_time_s)),
      ("  cutting      %12s"):format(f(r.cutting_s)),
      ("  rapid        %12s"):format(f(r.rapid_s)),
      ("  dwell        %12s"):format(f(r.dwell_s)),
      ("  tool change  %12s"):format(f(r.tool_change_s)),
      ("distance       %12s"):format(type(r.distance_mm) == "number" and ("%.1f mm"):format(r.distance_mm) or "-"),
      ("segments       %12d"):format(#segs),
    }
    scratch(lines, "partscope://dry-run")
  end)
end

--- The breakdown of `bufnr`'s dry run (the cycle-time lens's command, run by the server
--- with `show = false`: it is shown here); `callback(err, result)`, `result.text` the text.
function M.breakdown(bufnr, callback)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local client = partscope_clients(bufnr)[1]
  if client == nil then
    callback("no partscope client attached to this buffer", nil)
    return
  end
  local params = { command = M.BREAKDOWN_COMMAND, arguments = { vim.uri_from_bufnr(bufnr), { show = false } } }
  local handler = function(err, result)
    if err then
      callback(err.message or vim.inspect(err), nil)
    else
      callback(nil, result)
    end
  end
  if vim.fn.has("nvim-0.11") == 1 then
    client:request("workspace/executeCommand", params, handler, bufnr)
  else
    client.request("workspace/executeCommand", params, handler, bufnr)
  end
end

M.BREAKDOWN_COMMAND = "partscope.showBreakdown"

--- Shows the breakdown of `bufnr` in a scratch buffer named partscope://breakdown.
function M.show_breakdown(bufnr)
  M.breakdown(bufnr, function(err, r)
    if err then
      notify("breakdown failed: " .. err, vim.log.levels.ERROR)
      return
    end
    scratch(vim.split(r.text or "", "\n", { plain = true }), "partscope://breakdown")
  end)
end

-- The lens's command, run on the client: Neovim calls it for `vim.lsp.codelens.run()` instead
-- of sending it to the server, so the text lands in a buffer rather than the message area.
vim.lsp.commands[M.BREAKDOWN_COMMAND] = function(command, ctx)
  local bufnr = ctx.bufnr
  local uri = command.arguments and command.arguments[1]
  if type(uri) == "string" then
    bufnr = buffer_of(uri) or bufnr
  end
  M.show_breakdown(bufnr)
end

--- The command that opens a file in the browser: `open_cmd`, else the system's opener.
function M.opener()
  if config.open_cmd then
    return config.open_cmd
  end
  if vim.fn.has("mac") == 1 then
    return { "open" }
  end
  if vim.fn.has("win32") == 1 then
    return { "cmd", "/c", "start", "" }
  end
  return { "xdg-open" }
end

--- Writes the toolpath page of `bufnr`'s file (`partscope run FILE --html PAGE`, PAGE a
--- temporary file) and calls `callback(err, page)` when it is written.
function M.toolpath_page(bufnr, callback)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local file = vim.api.nvim_buf_get_name(bufnr)
  if file == "" or vim.fn.filereadable(file) == 0 then
    callback("the buffer has no file on disk; write it first", nil)
    return
  end
  local page = vim.fn.tempname() .. ".html"
  local stderr = {}
  local job = vim.fn.jobstart({ config.cmd[1], "run", file, "--html", page }, {
    stderr_buffered = true,
    on_stderr = function(_, data)
      stderr = data or {}
    end,
    on_exit = function(_, code)
      -- `run` exits 1 for a program with errors or a partial run; the page is written then too.
      if code <= 1 and vim.fn.filereadable(page) == 1 then
        callback(nil, page)
      else
        callback(("`partscope run --html` failed (%d): %s"):format(code, table.concat(stderr, " ")), nil)
      end
    end,
  })
  if job <= 0 then
    callback("cannot run " .. config.cmd[1], nil)
  end
end

local function open_toolpath()
  local bufnr = vim.api.nvim_get_current_buf()
  if vim.bo[bufnr].modified then
    notify("the buffer has unsaved changes; the page shows the file as saved", vim.log.levels.WARN)
  end
  M.toolpath_page(bufnr, function(err, page)
    if err then
      notify(err, vim.log.levels.ERROR)
      return
    end
    local cmd = vim.deepcopy(M.opener())
    table.insert(cmd, page)
    if vim.fn.jobstart(cmd, { detach = true }) <= 0 then
      notify(("cannot run %q to open %s"):format(cmd[1], page), vim.log.levels.ERROR)
    end
  end)
end

local function show_rule(code)
  if code == nil or code == "" then
    -- Default to the code of a diagnostic on the cursor line.
    local lnum = vim.api.nvim_win_get_cursor(0)[1] - 1
    for _, d in ipairs(vim.diagnostic.get(0, { lnum = lnum })) do
      if d.code ~= nil then
        code = tostring(d.code)
        break
      end
      local lsp = d.user_data and d.user_data.lsp
      if lsp and lsp.code ~= nil then
        code = tostring(lsp.code)
        break
      end
    end
  end
  if code == nil or code == "" then
    notify("usage: :PartscopeRule CODE (or put the cursor on a diagnostic)", vim.log.levels.WARN)
    return
  end
  local out = vim.fn.systemlist({ config.cmd[1], "rule", code })
  if vim.v.shell_error ~= 0 then
    table.insert(out, 1, ("`partscope rule %s` failed:"):format(code))
  end
  scratch(out, "partscope://rule/" .. code)
end

local function define_commands()
  vim.api.nvim_create_user_command("PartscopeDryRun", show_dry_run, { desc = "Partscope: cycle time of this buffer" })
  vim.api.nvim_create_user_command("PartscopeBreakdown", function()
    M.show_breakdown(vim.api.nvim_get_current_buf())
  end, { desc = "Partscope: where this buffer's cycle time goes" })
  vim.api.nvim_create_user_command("PartscopeToolpath", open_toolpath, {
    desc = "Partscope: open this file's toolpath in the browser",
  })
  vim.api.nvim_create_user_command("PartscopeRule", function(o)
    show_rule(o.args)
  end, { nargs = "?", desc = "Partscope: explain a rule code" })
  vim.api.nvim_create_user_command("PartscopeRestart", function()
    for _, c in ipairs(partscope_clients(0)) do
      vim.lsp.stop_client(c.id)
    end
    clients_by_root = {}
    vim.defer_fn(function()
      for _, b in ipairs(vim.api.nvim_list_bufs()) do
        if vim.api.nvim_buf_is_loaded(b) and vim.tbl_contains(config.filetypes, vim.bo[b].filetype) then
          M.attach(b)
        end
      end
    end, 500)
  end, { desc = "Partscope: restart the language server" })
end

--- Registers the G-code filetype and starts `partscope lsp` for G-code buffers.
function M.setup(opts)
  config = vim.tbl_deep_extend("force", vim.deepcopy(M.defaults), opts or {})
  -- Lists replace the defaults rather than merging index by index.
  for _, key in ipairs({ "cmd", "extensions", "patterns", "filetypes", "root_markers", "select", "ignore" }) do
    if opts and opts[key] ~= nil then
      config[key] = opts[key]
    end
  end
  warned_missing = false

  local group = vim.api.nvim_create_augroup("partscope", { clear = true })
  local patterns = {}
  for _, ext in ipairs(config.extensions) do
    table.insert(patterns, "*." .. ext)
    table.insert(patterns, "*." .. ext:upper())
  end
  for _, p in ipairs(config.patterns or {}) do
    table.insert(patterns, p)
  end
  -- Plain autocommands rather than vim.filetype.add: they behave the same on 0.7, where the
  -- Lua filetype detection is opt-in, and on current releases.
  vim.api.nvim_create_autocmd({ "BufRead", "BufNewFile" }, {
    group = group,
    pattern = patterns,
    callback = function(ev)
      vim.bo[ev.buf].filetype = "gcode"
    end,
  })
  vim.api.nvim_create_autocmd("FileType", {
    group = group,
    pattern = config.filetypes,
    callback = function(ev)
      M.attach(ev.buf)
    end,
  })
  if config.commands then
    define_commands()
  end
  vim.api.nvim_create_autocmd("BufEnter", {
    group = group,
    callback = function(ev)
      if stale_lenses[ev.buf] then
        M.refresh_lenses(ev.buf)
      end
    end,
  })

  -- Buffers opened before setup() ran.
  for _, b in ipairs(vim.api.nvim_list_bufs()) do
    if vim.api.nvim_buf_is_loaded(b) then
      local ext = vim.fn.fnamemodify(vim.api.nvim_buf_get_name(b), ":e"):lower()
      if vim.tbl_contains(config.filetypes, vim.bo[b].filetype) then
        M.attach(b)
      elseif ext ~= "" and vim.tbl_contains(config.extensions, ext) then
        vim.bo[b].filetype = "gcode"
      end
    end
  end
end

return M
