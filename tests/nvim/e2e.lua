-- End-to-end test of the Neovim plugin with the real language server, run headless:
--   nvim --headless --clean -u NONE -c "set rtp+=editors/neovim" -c "luafile tests/nvim/e2e.lua"
-- Prints 'N passed, M failed' and exits non-zero on failure.
local root = vim.fn.getcwd()
local bin = os.getenv('MILLPATH_BIN') or (root .. '/target/release/millpath')
local passed, failed = 0, 0
local function check(name, ok, detail)
  if ok then
    passed = passed + 1
    print('ok   ' .. name)
  else
    failed = failed + 1
    print('FAIL ' .. name .. ': ' .. tostring(detail))
  end
end
local function finish()
  print(string.format('%d passed, %d failed', passed, failed))
  vim.cmd(failed == 0 and 'qa!' or 'cq!')
end

local ok, err = pcall(function()
  local dir = vim.fn.tempname()
  vim.fn.mkdir(dir, 'p')
  vim.fn.writefile({ 'feed = 300', 'sweep_speed = 1000', 'sweep_height = 10' }, dir .. '/millpath.toml')
  -- a path whose start text lacks B
  local file = dir .. '/2030.mpath'
  vim.fn.writefile({
    'path 2030.1P {',
    '  start (0, 0)  M10x3 O2 T3 I1,5',
    '  end (20, 0)',
    '  mill (0, 0) -> (20, 0)',
    '}',
  }, file)
  vim.cmd('runtime! ftdetect/*.lua')
  require('millpath').setup({ cmd = { bin, 'lsp' } })
  vim.cmd('edit ' .. file)
  local main = vim.api.nvim_get_current_buf()
  check('filetype', vim.bo.filetype == 'millpath', vim.bo.filetype)

  vim.wait(15000, function() return #vim.diagnostic.get(0) > 0 end, 50)
  local diags = vim.diagnostic.get(0)
  local b
  for _, d in ipairs(diags) do
    if d.message == 'B value missing' then
      b = d
    end
  end
  check('"B value missing" diagnostic', b ~= nil, vim.inspect(diags))
  check('its range', b and b.lnum == 3 and b.col == 2 and b.end_lnum == 3 and b.end_col == 24, b and vim.inspect(b))

  local get = vim.lsp.get_clients or vim.lsp.get_active_clients
  local client = get({ name = 'millpath' })[1]
  -- Neovim pulls diagnostics (textDocument/diagnostic) from a server that offers them
  local provider = client.server_capabilities.diagnosticProvider
  check('diagnostics by pull', provider and provider.workspaceDiagnostics == true
    and client.capabilities.textDocument.diagnostic ~= nil, vim.inspect(provider))
  local function request(method, params)
    local res = client:request_sync(method, params, 10000, 0)
    return res and res.result, res and res.err
  end
  local hover = request('textDocument/hover', { textDocument = { uri = vim.uri_from_bufnr(0) }, position = { line = 3, character = 4 } })
  local md = hover and hover.contents and hover.contents.value or ''
  check('hover shows the inherited infeed and its origin', md:find('| I | 1,5 | path start (line 2) |', 1, true) ~= nil, md)
  check('hover shows the feed from millpath.toml', md:find('| F | 300 | millpath.toml', 1, true) ~= nil, md)

  -- fix the start text, save, and compare the preview with `millpath compile`
  vim.api.nvim_buf_set_lines(0, 1, 2, false, { '  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2' })
  vim.cmd('write')
  vim.wait(15000, function() return #vim.diagnostic.get(0) == 0 end, 50)
  check('the fix clears the diagnostics', #vim.diagnostic.get(0) == 0, vim.inspect(vim.diagnostic.get(0)))
  vim.api.nvim_win_set_cursor(0, { 4, 2 })
  local pbuf = require('millpath').preview()
  vim.wait(10000, function()
    local l = vim.api.nvim_buf_get_lines(pbuf, 0, 1, false)[1]
    return l == '%'
  end, 50)
  local preview = table.concat(vim.api.nvim_buf_get_lines(pbuf, 0, -1, false), '\n') .. '\n'
  vim.fn.system({ bin, 'compile', file })
  local compiled = table.concat(vim.fn.readfile(dir .. '/2030_Milling.gcode'), '\n') .. '\n'
  check('preview equals millpath compile output', preview == compiled, preview:sub(1, 200))
  -- the preview follows edits
  vim.api.nvim_buf_set_lines(0, 1, 2, false, { '  start (0, 0)  M10x3 O2 T3 I1 B-0,2' })
  vim.wait(10000, function()
    return table.concat(vim.api.nvim_buf_get_lines(pbuf, 0, -1, false), '\n') .. '\n' ~= preview
  end, 50)
  check('preview follows edits', table.concat(vim.api.nvim_buf_get_lines(pbuf, 0, -1, false), '\n') .. '\n' ~= preview, 'unchanged')
  -- running the code lens of the path opens its preview (a client-side command)
  vim.api.nvim_buf_delete(pbuf, { force = true })
  vim.api.nvim_win_set_cursor(0, { 1, 0 })
  vim.lsp.codelens.refresh({ bufnr = 0 })
  vim.wait(10000, function() return #vim.lsp.codelens.get(0) > 0 end, 50)
  local lenses = vim.lsp.codelens.get(0)
  check('a code lens on the path', #lenses > 0 and lenses[1].command and lenses[1].command.command == 'millpath.preview', vim.inspect(lenses))
  local lens_err
  local notify = vim.notify
  vim.notify = function(msg, level)
    if level and level >= vim.log.levels.WARN then lens_err = msg end
  end
  vim.lsp.codelens.run()
  vim.notify = notify
  local lbuf
  vim.wait(10000, function()
    lbuf = vim.b.millpath_preview
    return lbuf and vim.api.nvim_buf_is_valid(lbuf) and vim.api.nvim_buf_get_lines(lbuf, 0, 1, false)[1] == '%'
  end, 50)
  check('running the code lens opens the G-code preview', lbuf and vim.api.nvim_buf_is_valid(lbuf) and vim.api.nvim_buf_get_lines(lbuf, 0, 1, false)[1] == '%', lens_err or 'no preview')
  -- the toolpath page, served by the plugin's local server: page, data that follows the
  -- buffer, the cursor's element, clicks reported back (real HTTP through curl)
  vim.ui = vim.ui or {}
  local opened
  vim.ui.open = function(p) opened = p end
  local server = require('millpath').toolpath()
  vim.wait(10000, function() return opened ~= nil and server.version > 0 end, 50)
  check(':MillpathToolpath opens the served page', opened and opened:match('^http://127%.0%.0%.1:%d+/$') ~= nil, opened)
  local function http(args)
    local out
    vim.system(vim.list_extend({ 'curl', '-s', '-i', '--max-time', '5' }, args), { text = true }, function(r) out = r.stdout or '' end)
    vim.wait(6000, function() return out ~= nil end, 20)
    return out or ''
  end
  local page = http({ opened })
  check('the server gives the page', page:find('toolpath-data', 1, true) ~= nil, page:sub(1, 200))
  local data = http({ opened .. 'data' })
  check('the data holds the moves', data:find('"kind":"mill"', 1, true) ~= nil, data:sub(1, 300))
  local version = server.version
  vim.api.nvim_buf_set_lines(0, -2, -2, false, { '  # a comment' })
  vim.wait(10000, function() return server.version > version end, 50)
  check('the data follows the buffer', server.version > version, 'no new data')
  vim.api.nvim_win_set_cursor(0, { 4, 0 })
  vim.api.nvim_exec_autocmds('CursorMoved', { buffer = 0 })
  local hl = http({ opened .. 'highlight' })
  check('the cursor line is served for highlighting', hl:find('"line":3', 1, true) ~= nil, hl)
  local revealed
  require('millpath').on_reveal = function(msg) revealed = msg end
  vim.api.nvim_win_set_cursor(0, { 1, 0 })
  local body = vim.json.encode({ type = 'reveal', source = { file = vim.api.nvim_buf_get_name(0), line = 3, character = 2 }, gcodeLine = 12 })
  http({ '-X', 'POST', '--data-binary', body, opened .. 'click' })
  vim.wait(5000, function() return revealed ~= nil end, 20)
  local cur = vim.api.nvim_win_get_cursor(0)
  check('a click on the page moves the cursor to the element', cur[1] == 4 and cur[2] == 2, vim.inspect(cur))
  -- the page itself in real Chromium: it draws the served data, highlights the element under
  -- the cursor, and a real click on a move reaches Neovim
  local playwright = root .. '/editors/vscode/node_modules/playwright-core'
  if vim.fn.isdirectory(playwright) == 1 and vim.fn.executable('/usr/bin/chromium') == 1 then
    revealed = nil
    vim.api.nvim_win_set_cursor(0, { 4, 0 })
    vim.api.nvim_exec_autocmds('CursorMoved', { buffer = 0 })
    local out
    vim.system({ 'node', root .. '/tests/nvim/page_click.mjs', opened }, { text = true }, function(r)
      out = { code = r.code, stdout = r.stdout or '', stderr = r.stderr or '' }
    end)
    vim.wait(60000, function() return out ~= nil and revealed ~= nil end, 50)
    local res = out and out.code == 0 and vim.json.decode(out.stdout) or nil
    check('Chromium draws the served page and highlights the cursor\'s element', res and res.drawn > 0 and res.highlighted > 0, vim.inspect(out))
    check('a real click in Chromium moves the cursor to the clicked element', revealed ~= nil and res ~= nil
      and revealed.source.line == res.clicked.line and vim.api.nvim_win_get_cursor(0)[1] == res.clicked.line + 1
      and revealed.gcodeLine == res.clicked.gcodeLine, vim.inspect({ revealed = revealed, res = res }))
  else
    print('skip the page in Chromium: no editors/vscode/node_modules (npm ci) or /usr/bin/chromium')
  end

  -- folding through the server (vim.lsp.foldexpr): the path folds from its header
  vim.wo.foldmethod = 'expr'
  vim.wo.foldexpr = 'v:lua.vim.lsp.foldexpr()'
  vim.wait(10000, function() return vim.fn.foldlevel(2) > 0 end, 50)
  check('folding ranges: the path body folds', vim.fn.foldlevel(1) > 0 and vim.fn.foldlevel(2) > 0, vim.fn.foldlevel(2))
  vim.wo.foldmethod = 'manual'

  -- rename across files: a project on disk embeds the path; vim.lsp.buf.rename edits both
  local project = dir .. '/2040.mpath'
  vim.fn.writefile({
    'path 2040.1P {',
    '  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2',
    '  end (40, 0)',
    '  sweep (0, 0) -> (10, 0)',
    '  sub (10, 0) -> (30, 0)  >2030.1P  # Grüße 😀',
    '  sweep (30, 0) -> (40, 0)',
    '}',
  }, project)
  vim.api.nvim_win_set_cursor(0, { 1, 7 })
  vim.lsp.buf.rename('2030.7Q')
  local pbufnr
  vim.wait(10000, function()
    pbufnr = vim.fn.bufnr(project)
    return pbufnr > 0 and vim.api.nvim_buf_get_lines(pbufnr, 4, 5, false)[1] ~= nil
      and vim.api.nvim_buf_get_lines(pbufnr, 4, 5, false)[1]:find('>2030.7Q', 1, true) ~= nil
  end, 50)
  check('rename edits the path header', vim.api.nvim_buf_get_lines(0, 0, 1, false)[1] == 'path 2030.7Q {', vim.api.nvim_buf_get_lines(0, 0, 1, false)[1])
  local embedded = pbufnr > 0 and vim.api.nvim_buf_get_lines(pbufnr, 4, 5, false)[1] or ''
  check('rename edits the embedding in the other file', embedded == '  sub (10, 0) -> (30, 0)  >2030.7Q  # Grüße 😀', embedded)
  -- an invalid name is refused with the server's message; nothing changes
  local msg
  vim.notify = function(m, level) msg = m end
  vim.lsp.buf.rename('Nut')
  vim.wait(10000, function() return msg ~= nil end, 50)
  vim.notify = notify
  check('an invalid new name is refused with a reason', msg and msg:find('not a valid path name', 1, true) ~= nil, msg)
  check('and nothing is renamed', vim.api.nvim_buf_get_lines(0, 0, 1, false)[1] == 'path 2030.7Q {', vim.api.nvim_buf_get_lines(0, 0, 1, false)[1])

  -- document highlight: both uses of the name in the project
  local hl = request('textDocument/documentHighlight', { textDocument = { uri = vim.uri_from_fname(project) }, position = { line = 4, character = 28 } })
  check('document highlight of the embedding', hl and #hl == 1 and hl[1].range.start.line == 4 and hl[1].range.start.character == 26, vim.inspect(hl))

  -- call hierarchy over subpath embedding, through Neovim's own commands (quickfix list)
  vim.cmd('silent! wall')
  vim.api.nvim_set_current_buf(main)
  vim.api.nvim_win_set_cursor(0, { 1, 7 })
  vim.fn.setqflist({}, 'r')
  vim.lsp.buf.incoming_calls()
  vim.wait(10000, function() return #vim.fn.getqflist() > 0 end, 50)
  local qf = vim.fn.getqflist()
  local function at(e) return e and { vim.api.nvim_buf_get_name(e.bufnr), e.lnum, e.col, e.text } end
  check('incoming calls: the project embeds the path (at its >NAME)', #qf == 1
    and vim.api.nvim_buf_get_name(qf[1].bufnr) == project and qf[1].lnum == 5 and qf[1].col == 27
    and qf[1].text == '2040.1P', vim.inspect(vim.tbl_map(at, qf)))
  vim.cmd('cclose')
  vim.cmd('edit ' .. project)
  vim.api.nvim_win_set_cursor(0, { 1, 7 })
  vim.fn.setqflist({}, 'r')
  vim.lsp.buf.outgoing_calls()
  vim.wait(10000, function() return #vim.fn.getqflist() > 0 end, 50)
  qf = vim.fn.getqflist()
  check('outgoing calls: the project embeds 2030.7Q', #qf == 1 and qf[1].text == '2030.7Q'
    and vim.api.nvim_buf_get_name(qf[1].bufnr) == file and qf[1].lnum == 5, vim.inspect(vim.tbl_map(at, qf)))
  vim.cmd('cclose')

  -- a post file (posts/*.toml): the server attaches and shows the post loader's located error
  vim.fn.mkdir(dir .. '/posts', 'p')
  local post = dir .. '/posts/mine.toml'
  local shown = vim.fn.systemlist({ bin, 'post', 'show', 'grbl' })
  local tline
  for i, l in ipairs(shown) do
    if l == 'tool = "T{tool_number}"' then
      shown[i] = 'tool = "T{tool_numbr}"'
      tline = i
    end
  end
  vim.fn.writefile(shown, post)
  vim.cmd('filetype on')
  vim.cmd('edit ' .. post)
  check('a post file is TOML', vim.bo.filetype == 'toml', vim.bo.filetype)
  vim.wait(15000, function() return #vim.diagnostic.get(0) > 0 end, 50)
  local pd = vim.diagnostic.get(0)
  check('the post error as a diagnostic, at its line', tline and #pd == 1 and pd[1].lnum == tline - 1
    and pd[1].message:find('templates.tool: unknown variable {tool_numbr}', 1, true) ~= nil, vim.inspect(pd))
  -- another TOML file: no millpath client
  local other = dir .. '/other.toml'
  vim.fn.writefile({ '[a]', 'b = 1' }, other)
  vim.cmd('edit ' .. other)
  vim.wait(500)
  check('no millpath client for another TOML file', require('millpath')._client_for(0) == nil)
end)
if not ok then
  check('no Lua error', false, err)
end
finish()
