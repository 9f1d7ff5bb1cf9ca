-- :MillpathDiff [REV] as a user runs it, in a scratch git repository with two commits: the
-- report of `millpath diff REV -- FILE` in a scratch split, the visual diff's page written
-- to the temporary file whose path it prints; an unknown revision is an error, no split.
--   nvim --headless --clean --cmd "set rtp^=editors/neovim" -c "luafile tests/nvim/diff.lua"
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

local ok, err = pcall(function()
  local millpath = require('millpath')
  millpath.config.cmd = { bin, 'lsp' }
  local dir = vim.fn.tempname()
  vim.fn.mkdir(dir, 'p')
  local function git(...)
    local out = vim.fn.system({ 'git', '-C', dir, ... })
    assert(vim.v.shell_error == 0, 'git ' .. table.concat({ ... }, ' ') .. ': ' .. out)
  end
  local function slot(x)
    return { 'path 2001.1P {', '  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2', '  end (30, 0)',
      '  sweep (0, 0) -> (5, 0)', '  mill (5, 0) -> (' .. x .. ', 0)', '  sweep (' .. x .. ', 0) -> (30, 0)', '}' }
  end
  local file = dir .. '/2001.mpath'
  git('init', '-q')
  git('config', 'user.email', 't@example.com')
  git('config', 'user.name', 't')
  vim.fn.writefile(slot(25), file)
  git('add', '.')
  git('commit', '-qm', 'first')
  vim.fn.writefile(slot(20), file)
  git('commit', '-qam', 'second')

  vim.cmd('edit ' .. file)
  local src = vim.api.nvim_get_current_buf()
  -- no change since HEAD: a report that says so
  vim.cmd('MillpathDiff')
  local buf = vim.api.nvim_get_current_buf()
  local text = table.concat(vim.api.nvim_buf_get_lines(buf, 0, -1, false), '\n')
  check(':MillpathDiff opens a scratch split', buf ~= src and vim.bo[buf].buftype == 'nofile', vim.bo[buf].buftype)
  check('against HEAD: no change', text:find('No change.', 1, true) ~= nil, text)
  vim.cmd('close')

  vim.cmd('MillpathDiff HEAD~1')
  buf = vim.api.nvim_get_current_buf()
  text = table.concat(vim.api.nvim_buf_get_lines(buf, 0, -1, false), '\n')
  check('against HEAD~1: the report names the path as changed', text:find('2001.1P: changed', 1, true) ~= nil, text)
  check('against HEAD~1: the moved mill', text:find('mill (5, 0) -> (20, 0)', 1, true) ~= nil, text)
  local said = vim.fn.execute('messages')
  local page = said:match('the visual diff is (%S+%.html)')
  check('the page path is printed', page ~= nil, said)
  local html = page and table.concat(vim.fn.readfile(page), '\n') or ''
  check('the page is the visual diff', html:find('<svg', 1, true) ~= nil and html:find('2001', 1, true) ~= nil,
    html:sub(1, 200))
  vim.cmd('close')

  local windows = #vim.api.nvim_list_wins()
  -- the error is notified (headless, an ErrorMsg is raised as an error)
  local _, msg = pcall(vim.cmd, 'MillpathDiff no-such-rev')
  check('an unknown revision is an error that names it', tostring(msg):find('no-such-rev', 1, true) ~= nil, msg)
  check('an unknown revision opens no split', #vim.api.nvim_list_wins() == windows, #vim.api.nvim_list_wins())
end)
if not ok then
  check('no Lua error', false, err)
end
print(string.format('%d passed, %d failed', passed, failed))
vim.cmd(failed == 0 and 'qa!' or 'cq!')
