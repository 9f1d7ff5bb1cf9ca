-- The plugin as a user starts it, on every Neovim it supports (CI: Debian 12's 0.7 and a
-- recent one): nvim --clean with the plugin on the runtime path, so Neovim's own file type
-- detection runs the plugin's ftdetect; setup() as in an init.lua; then open a .mpath file.
--   nvim --headless --clean --cmd "set rtp^=editors/neovim" -c "luafile tests/nvim/basic.lua"
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
local v = vim.version()
print(string.format('Neovim %d.%d.%d', v.major, v.minor, v.patch))

local ok, err = pcall(function()
  local millpath = require('millpath')
  check('setup accepts this Neovim (' .. tostring(millpath.min_version) .. ' or later)',
    millpath.setup({ cmd = { bin, 'lsp' } }) == true, 'refused')
  local dir = vim.fn.tempname()
  vim.fn.mkdir(dir, 'p')
  vim.fn.writefile({ 'feed = 300', 'sweep_speed = 1000', 'sweep_height = 10' }, dir .. '/millpath.toml')
  -- a comment first: filetype.vim's fallback would call this file `conf`
  local file = dir .. '/2030.mpath'
  vim.fn.writefile({
    '# a path whose start text lacks B',
    'path 2030.1P {',
    '  start (0, 0)  M10x3 O2 T3 I1,5',
    '  end (20, 0)',
    '  mill (0, 0) -> (20, 0)',
    '}',
  }, file)
  vim.cmd('edit ' .. file)
  local main = vim.api.nvim_get_current_buf()
  check('filetype millpath', vim.bo.filetype == 'millpath', vim.bo.filetype)

  local client
  vim.wait(15000, function()
    client = millpath._client_for(main)
    return client ~= nil and client.initialized ~= false
  end, 50)
  check('the server attaches to the buffer', client ~= nil and client.name == 'millpath', 'no client')

  vim.wait(15000, function() return #vim.diagnostic.get(main) > 0 end, 50)
  local b
  for _, d in ipairs(vim.diagnostic.get(main)) do
    if d.message == 'B value missing' then
      b = d
    end
  end
  check('it publishes "B value missing"', b ~= nil, vim.inspect(vim.diagnostic.get(main)))
  check('at the mill line', b and b.lnum == 4 and b.col == 2, b and vim.inspect(b))

  -- the preview: a request of the plugin's own (the call differs from 0.11 on)
  vim.api.nvim_buf_set_lines(main, 2, 3, false, { '  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2' })
  vim.api.nvim_win_set_cursor(0, { 5, 2 })
  local pbuf = millpath.preview()
  vim.wait(10000, function()
    return pbuf and vim.api.nvim_buf_get_lines(pbuf, 0, 1, false)[1] == '%'
  end, 50)
  local gcode = pbuf and table.concat(vim.api.nvim_buf_get_lines(pbuf, 0, -1, false), '\n') or ''
  check(':MillpathPreview shows the G-code', gcode:find('\n%%$') ~= nil and gcode:find('G1', 1, true) ~= nil, gcode:sub(1, 200))

  -- a second file of the folder: detected too, and served by the same server
  local other = dir .. '/2031.mpath'
  vim.fn.writefile({ 'path 2031.1P {', '  start (0, 0)  M10x3 O2 T3 I1', '  end (5, 0)', '  mill (0, 0) -> (5, 0)', '}' }, other)
  vim.cmd('edit ' .. other)
  local second
  vim.wait(10000, function()
    second = millpath._client_for(vim.api.nvim_get_current_buf())
    return second ~= nil
  end, 50)
  check('a second file of the folder shares the server', second ~= nil and client ~= nil and second.id == client.id,
    second and second.id)
end)
if not ok then
  check('no Lua error', false, err)
end
print(string.format('%d passed, %d failed', passed, failed))
vim.cmd(failed == 0 and 'qa!' or 'cq!')
