-- Commands of the millpath plugin; the language server starts with require('millpath').setup().
if vim.g.loaded_millpath then
  return
end
vim.g.loaded_millpath = true
if vim.fn.has('nvim-0.7') == 0 then
  vim.api.nvim_echo({ { 'millpath: Neovim 0.7 or later is needed; the plugin is off', 'ErrorMsg' } }, true, {})
  return
end

vim.api.nvim_create_user_command('MillpathPreview', function(args)
  require('millpath').preview(args.args ~= '' and args.args or nil)
end, { nargs = '?', desc = 'G-code of the path under the cursor, in a split that follows edits' })

vim.api.nvim_create_user_command('MillpathDxfToText', function(args)
  require('millpath').dxf_to_text(args.args ~= '' and args.args or nil)
end, { nargs = '?', complete = 'file', desc = 'Open a DXF drawing as MillPath text' })

vim.api.nvim_create_user_command('MillpathToolpath', function(args)
  require('millpath').toolpath(args.args ~= '' and args.args or nil)
end, { nargs = '?', desc = 'Toolpath of the path under the cursor, in the browser' })

vim.api.nvim_create_user_command('MillpathDiff', function(args)
  require('millpath').diff(args.args ~= '' and args.args or nil)
end, { nargs = '?', desc = "What the file's changes since REV (default HEAD) do to the part" })
