-- *.mpath files are MillPath paths
if vim.filetype and vim.filetype.add then
  vim.filetype.add({ extension = { mpath = 'millpath' } })
else
  vim.cmd([[autocmd BufRead,BufNewFile *.mpath setfiletype millpath]])
end
