-- millpath for Neovim: filetype, language server (`millpath lsp`), G-code preview, DXF to text.
local M = {}

M.config = {
  -- the server command
  cmd = { 'millpath', 'lsp' },
  -- machine settings sent as initialization options; they override millpath.toml
  -- (feed, sweep_speed, sweep_height, probe_feed, search_dirs, lang, ...)
  settings = {},
  -- a compiled tree-sitter parser for highlighting (see the README); nil: none
  parser_path = nil,
}

local function root_dir(fname)
  local found = vim.fs and vim.fs.find and vim.fs.find({ 'millpath.toml', '.git' }, { upward = true, path = vim.fs.dirname(fname) })[1]
  if found then
    return vim.fs.dirname(found)
  end
  return vim.fn.fnamemodify(fname, ':p:h')
end

--- Whether the server serves a buffer: MillPath text, millpath.toml (completion and hover of
--- post names) and the post files of a posts/ folder (the post loader's errors as diagnostics);
--- no other TOML file (a Cargo.toml starts no millpath server).
local function serves(name, filetype)
  if filetype == 'millpath' then
    return true
  end
  local base = vim.fn.fnamemodify(name, ':t')
  local folder = vim.fn.fnamemodify(name, ':h:t')
  return base == 'millpath.toml' or (folder == 'posts' and base:match('%.toml$') ~= nil)
end
M._serves = serves

--- The language clients attached to a buffer (get_clients: 0.10; get_active_clients takes a
--- filter from 0.8; 0.7 has buf_get_clients).
local function clients_of(bufnr)
  if vim.lsp.get_clients then
    return vim.lsp.get_clients({ bufnr = bufnr })
  elseif vim.fn.has('nvim-0.8') == 1 then
    return vim.lsp.get_active_clients({ bufnr = bufnr })
  end
  return vim.tbl_values(vim.lsp.buf_get_clients(bufnr))
end

local function client_for(bufnr)
  for _, c in ipairs(clients_of(bufnr)) do
    if c.name == 'millpath' then
      return c
    end
  end
end
M._client_for = client_for

--- Neovim 0.7 has no vim.lsp.start: one client per project folder, started once and attached
--- to each of its buffers.
local started = {}
local function start_07(conf, bufnr)
  local id = started[conf.root_dir]
  local client = id and vim.lsp.get_client_by_id(id)
  if not client or client.is_stopped() then
    id = vim.lsp.start_client(conf)
    started[conf.root_dir] = id
  end
  if id then
    vim.lsp.buf_attach_client(bufnr, id)
  end
end

--- The oldest Neovim the plugin works with (nvim_create_autocmd and vim.lsp.commands are 0.7's).
M.min_version = '0.7'

--- Sets up the language server for *.mpath buffers, millpath.toml and posts/*.toml (Neovim 0.11: vim.lsp.config/enable;
--- 0.8-0.10: vim.lsp.start; 0.7: vim.lsp.start_client and buf_attach_client).
function M.setup(opts)
  if vim.fn.has('nvim-' .. M.min_version) == 0 then
    vim.notify('millpath: Neovim ' .. M.min_version .. ' or later is needed; the plugin is off',
      vim.log.levels.ERROR)
    return false
  end
  M.config = vim.tbl_deep_extend('force', M.config, opts or {})
  local cfg = M.config
  -- the code lenses' command is a client-side one (arguments: document URI, path name): it
  -- opens the preview of that path (the server's own command is millpath.server.preview)
  vim.lsp.commands['millpath.preview'] = function(command)
    local args = command.arguments or {}
    local bufnr = args[1] and vim.uri_to_bufnr(args[1]) or vim.api.nvim_get_current_buf()
    if bufnr ~= vim.api.nvim_get_current_buf() then
      vim.api.nvim_set_current_buf(bufnr)
    end
    M.preview(args[2])
  end
  if cfg.parser_path and vim.treesitter and vim.treesitter.language and vim.treesitter.language.add then
    pcall(vim.treesitter.language.add, 'millpath', { path = cfg.parser_path })
  end
  if vim.lsp.config and vim.lsp.enable then
    vim.lsp.config('millpath', {
      cmd = cfg.cmd,
      filetypes = { 'millpath', 'toml' },
      -- not called for a TOML file the server does not serve: no client for it
      root_dir = function(bufnr, on_dir)
        local name = vim.api.nvim_buf_get_name(bufnr)
        if serves(name, vim.bo[bufnr].filetype) then
          on_dir(root_dir(name))
        end
      end,
      init_options = cfg.settings,
    })
    vim.lsp.enable('millpath')
    return true
  end
  vim.api.nvim_create_autocmd('FileType', {
    pattern = { 'millpath', 'toml' },
    callback = function(ev)
      local name = vim.api.nvim_buf_get_name(ev.buf)
      if not serves(name, vim.bo[ev.buf].filetype) then
        return
      end
      local conf = { name = 'millpath', cmd = cfg.cmd, root_dir = root_dir(name), init_options = cfg.settings }
      if vim.lsp.start then
        vim.lsp.start(conf, { bufnr = ev.buf })
      else
        start_07(conf, ev.buf)
      end
    end,
  })
  return true
end

--- A request to the server (the method call changed in Neovim 0.11).
local function request(client, method, params, handler, bufnr)
  if vim.fn.has('nvim-0.11') == 1 then
    client:request(method, params, handler, bufnr)
  else
    client.request(method, params, handler, bufnr)
  end
end

--- The name of the path block around the cursor (or the first one).
local function path_at_cursor(bufnr)
  local row = vim.api.nvim_win_get_cursor(0)[1]
  local lines = vim.api.nvim_buf_get_lines(bufnr, 0, -1, false)
  local name
  for i = row, 1, -1 do
    name = lines[i] and lines[i]:match('^%s*path%s+(%S+)%s*{')
    if name then
      return name
    end
  end
  for _, l in ipairs(lines) do
    name = l:match('^%s*path%s+(%S+)%s*{')
    if name then
      return name
    end
  end
end

--- The current buffer, its millpath client (or a warning) and the path to work on.
local function current(name)
  local src = vim.api.nvim_get_current_buf()
  local client = client_for(src)
  if not client then
    vim.notify('millpath: the language server is not running for this buffer', vim.log.levels.WARN)
  end
  return src, client, name or path_at_cursor(src)
end

--- The preview's text: the G-code, or for a path `millpath compile` would refuse its errors
--- (the result's `errors`) as comment lines instead; errors beside G-code come first.
local function preview_text(result)
  local lines = {}
  for _, e in ipairs(result.errors or {}) do
    local safe = tostring(e):gsub('%(', '['):gsub('%)', ']'):gsub('\r?\n', ' ')
    table.insert(lines, '(millpath: ' .. safe .. ')')
  end
  if #lines == 0 then
    return result.gcode or ''
  end
  return table.concat(lines, '\n') .. '\n' .. (result.gcode or '')
end
M._preview_text = preview_text

local function show(buf, result, err)
  local text
  if err then
    text = '(millpath: ' .. (err.message or vim.inspect(err)) .. ')'
  else
    text = preview_text(result)
  end
  local lines = vim.split(text, '\n', { plain = true })
  if lines[#lines] == '' then
    table.remove(lines)
  end
  vim.bo[buf].modifiable = true
  vim.api.nvim_buf_set_lines(buf, 0, -1, false, lines)
  vim.bo[buf].modifiable = false
end

--- Opens (or refreshes) the G-code preview of the path under the cursor in a split that
--- follows every edit of the source buffer.
-- Calls `refresh` once per burst of edits in `src`, `delay_ms` after its first change (the
-- server has the new text by then), while `wanted()` holds. on_lines sees every change:
-- typing, API edits, undo.
local function follow_edits(src, delay_ms, wanted, refresh)
  local pending = false
  vim.api.nvim_buf_attach(src, false, {
    on_lines = function()
      if not wanted() then
        return true -- detach
      end
      if not pending then
        pending = true
        vim.defer_fn(function()
          pending = false
          refresh()
        end, delay_ms)
      end
    end,
  })
end

function M.preview(name)
  local src, client
  src, client, name = current(name)
  if not client then
    return
  end
  local buf = vim.b[src].millpath_preview
  if not buf or not vim.api.nvim_buf_is_valid(buf) then
    buf = vim.api.nvim_create_buf(false, true)
    vim.bo[buf].filetype = 'gcode'
    vim.bo[buf].bufhidden = 'wipe'
    vim.api.nvim_buf_set_name(buf, 'millpath://preview/' .. (name or '') .. '/' .. buf)
    vim.b[src].millpath_preview = buf
    local win = vim.api.nvim_get_current_win()
    vim.cmd('vsplit')
    vim.api.nvim_win_set_buf(0, buf)
    vim.api.nvim_set_current_win(win)
  end
  local function refresh()
    local params = { textDocument = { uri = vim.uri_from_bufnr(src) }, path = name }
    local function handler(err, result)
      if vim.api.nvim_buf_is_valid(buf) then
        show(buf, result, err)
      end
    end
    request(client, 'millpath/gcodePreview', params, handler, src)
  end
  refresh()
  if not vim.b[src].millpath_preview_follow then
    vim.b[src].millpath_preview_follow = true
    follow_edits(src, 80, function() return vim.api.nvim_buf_is_valid(buf) end, refresh)
  end
  return buf
end

local function plugin_root()
  local src = debug.getinfo(1, 'S').source:gsub('^@', '')
  return vim.fn.fnamemodify(src, ':p:h:h:h')
end

--- Jumps to what a click on the page names: the element's line in its file, and the move's
--- line in the G-code preview when one is open.
local function reveal(src, msg)
  local s = msg.source
  if type(s) == 'table' and type(s.file) == 'string' and type(s.line) == 'number' then
    local win = vim.fn.bufwinid(src)
    if win ~= -1 then vim.api.nvim_set_current_win(win) end
    if vim.api.nvim_buf_get_name(src) ~= s.file then
      vim.cmd('edit ' .. vim.fn.fnameescape(s.file))
    elseif win == -1 then
      vim.api.nvim_set_current_buf(src)
    end
    local last = vim.api.nvim_buf_line_count(0)
    vim.api.nvim_win_set_cursor(0, { math.min(s.line + 1, last), s.character or 0 })
  end
  local pbuf = vim.b[src].millpath_preview
  local line = tonumber(msg.gcodeLine)
  if line and pbuf and vim.api.nvim_buf_is_valid(pbuf) then
    local pwin = vim.fn.bufwinid(pbuf)
    if pwin ~= -1 then
      vim.api.nvim_win_set_cursor(pwin, { math.min(line, vim.api.nvim_buf_line_count(pbuf)), 0 })
    end
  end
  if M.on_reveal then M.on_reveal(msg) end
end

--- Opens the toolpath view of the path under the cursor in the browser: a local server
--- (millpath.toolpath_server) serves the page of editors/toolpath, which follows the buffer
--- (new data after every edit), highlights the moves of the element under the cursor and
--- reports clicks back (the cursor jumps to the element and to its G-code line).
function M.toolpath(name)
  local src, client
  src, client, name = current(name)
  if not client then
    return
  end
  local page = plugin_root() .. '/../toolpath/toolpath.html'
  local ok, template = pcall(vim.fn.readfile, page)
  if not ok then
    vim.notify('millpath: toolpath page not found at ' .. page, vim.log.levels.ERROR)
    return
  end
  local server = M.toolpath_servers[src]
  if not server then
    server = require('millpath.toolpath_server').start(table.concat(template, '\n'), function(msg)
      reveal(src, msg)
    end)
    M.toolpath_servers[src] = server
    local function refresh()
      local params = { textDocument = { uri = vim.uri_from_bufnr(src) }, path = name }
      request(client, 'millpath/toolpath', params, function(err, result)
        if err then
          server:set_data(vim.json.encode({ error = err.message or vim.inspect(err), moves = {} }))
        else
          server:set_data(vim.json.encode(result))
        end
      end, src)
    end
    server.refresh = refresh
    follow_edits(src, 150, function() return M.toolpath_servers[src] == server end, refresh)
    local group = vim.api.nvim_create_augroup('millpath_toolpath_' .. src, { clear = true })
    vim.api.nvim_create_autocmd({ 'CursorMoved', 'CursorMovedI' }, {
      group = group,
      callback = function(ev)
        if vim.bo[ev.buf].filetype == 'millpath' then
          server:set_highlight(vim.api.nvim_buf_get_name(ev.buf), vim.api.nvim_win_get_cursor(0)[1] - 1)
        end
      end,
    })
    local function stop()
      server:stop()
      M.toolpath_servers[src] = nil
    end
    vim.api.nvim_create_autocmd('BufWipeout', { group = group, buffer = src, callback = stop })
    vim.api.nvim_create_autocmd('VimLeavePre', { group = group, callback = stop })
  end
  server.refresh()
  M.last_toolpath = server.url
  if vim.ui and vim.ui.open then
    vim.ui.open(server.url)
  else
    vim.fn.jobstart({ 'xdg-open', server.url }, { detach = true })
  end
  return server
end
M.toolpath_servers = {}

--- Opens a DXF drawing as MillPath text in a new buffer.
function M.dxf_to_text(file)
  file = file or vim.api.nvim_buf_get_name(0)
  local exe = M.config.cmd[1]
  local out = vim.fn.system({ exe, 'dxf2text', file })
  if vim.v.shell_error ~= 0 then
    vim.notify('millpath dxf2text: ' .. out, vim.log.levels.ERROR)
    return
  end
  vim.cmd('enew')
  local lines = vim.split(out, '\n', { plain = true })
  if lines[#lines] == '' then
    table.remove(lines)
  end
  vim.api.nvim_buf_set_lines(0, 0, -1, false, lines)
  vim.bo.filetype = 'millpath'
  vim.api.nvim_buf_set_name(0, vim.fn.fnamemodify(file, ':r') .. '.mpath')
end

--- `:MillpathDiff [REV]`: what the file's changes since REV (default HEAD) do to the part
--- (`millpath diff REV -- FILE`) in a scratch split, and the visual diff (`--html`) in a
--- temporary file whose path is printed. Returns the report's buffer and the page's path.
function M.diff(rev, file)
  rev = rev or 'HEAD'
  file = file or vim.api.nvim_buf_get_name(0)
  if file == '' then
    vim.notify('millpath diff: the buffer has no file', vim.log.levels.ERROR)
    return nil
  end
  local html = vim.fn.tempname() .. '-diff.html'
  local out = vim.fn.system({ M.config.cmd[1], 'diff', rev, '--html', html, '--', file })
  -- exit status 1 means "changed", not a failure
  if vim.v.shell_error > 1 then
    vim.notify('millpath diff: ' .. out, vim.log.levels.ERROR)
    return nil
  end
  vim.cmd('new')
  local buf = vim.api.nvim_get_current_buf()
  vim.bo[buf].buftype = 'nofile'
  vim.bo[buf].bufhidden = 'wipe'
  vim.bo[buf].swapfile = false
  local lines = vim.split(out, '\n', { plain = true })
  if lines[#lines] == '' then
    table.remove(lines)
  end
  vim.api.nvim_buf_set_lines(buf, 0, -1, false, lines)
  vim.bo[buf].modifiable = false
  vim.api.nvim_echo({ { 'millpath diff: the visual diff is ' .. html } }, true, {})
  return buf, html
end

return M
