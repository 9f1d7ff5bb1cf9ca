-- *.mpath files are MillPath paths. vim.filetype.add exists from Neovim 0.7 but only takes
-- effect from 0.8 (0.7 detects with filetype.vim unless g:do_filetype_lua is set): older
-- versions get an autocmd, which filetype.vim's detection runs before its `conf` fallback.
if vim.fn.has('nvim-0.8') == 1 and vim.filetype and vim.filetype.add then
  vim.filetype.add({ extension = { mpath = 'millpath' } })
else
  vim.cmd([[autocmd BufRead,BufNewFile *.mpath setfiletype millpath]])
end
