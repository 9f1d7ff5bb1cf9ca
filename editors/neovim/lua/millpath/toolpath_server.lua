-- A small HTTP server on 127.0.0.1 (libuv, inside Neovim) for the toolpath page: it serves the
-- page, the current toolpath data (the page polls it and follows the buffer), the element
-- under the cursor (the page highlights its moves) and receives the page's clicks.
--   GET  /           the page (editors/toolpath/toolpath.html, data loaded from /data)
--   GET  /data       the toolpath JSON, ETag = version; 304 while unchanged
--   GET  /highlight  {"seq", "file", "line"} of the cursor in the source
--   POST /click      {"source": {file, line, character}, "gcodeLine"} → on_click(msg)
local uv = vim.uv or vim.loop
local S = {}
S.__index = S

--- A request larger than this is refused (the page sends small JSON objects).
local MAX_REQUEST = 1024 * 1024

local function respond(sock, status, ctype, body, extra)
  local head = {
    'HTTP/1.1 ' .. status,
    'Content-Type: ' .. ctype,
    'Content-Length: ' .. #body,
    'Cache-Control: no-store',
    'Connection: close',
  }
  for k, v in pairs(extra or {}) do
    table.insert(head, k .. ': ' .. v)
  end
  sock:write(table.concat(head, '\r\n') .. '\r\n\r\n' .. body, function()
    sock:shutdown(function() sock:close() end)
  end)
end

--- Starts a server; `page` is the page's HTML, `on_click(msg)` runs on the main loop.
function S.start(page, on_click)
  local self = setmetatable({ page = page, data = 'null', version = 0, highlight = nil, seq = 0, on_click = on_click }, S)
  local server = uv.new_tcp()
  server:bind('127.0.0.1', 0)
  server:listen(16, function(err)
    if err then return end
    local sock = uv.new_tcp()
    server:accept(sock)
    local buf = ''
    sock:read_start(function(rerr, chunk)
      if rerr or not chunk then
        sock:close()
        return
      end
      buf = buf .. chunk
      if #buf > MAX_REQUEST then
        sock:read_stop()
        respond(sock, '413 Payload Too Large', 'text/plain', 'too large')
        return
      end
      local head_end = buf:find('\r\n\r\n', 1, true)
      if not head_end then return end
      local head = buf:sub(1, head_end - 1)
      local len = tonumber(head:match('[Cc]ontent%-[Ll]ength:%s*(%d+)')) or 0
      if #buf < head_end + 3 + len then return end
      sock:read_stop()
      local body = buf:sub(head_end + 4, head_end + 3 + len)
      local method, target = head:match('^(%u+) (%S+)')
      self:handle(sock, method, target, head, body)
    end)
  end)
  self.server = server
  self.port = server:getsockname().port
  self.url = 'http://127.0.0.1:' .. self.port .. '/'
  return self
end

function S:handle(sock, method, target, head, body)
  local etag = '"' .. self.version .. '"'
  if method == 'GET' and target == '/' then
    respond(sock, '200 OK', 'text/html; charset=utf-8', self.page)
  elseif method == 'GET' and target == '/data' then
    if head:match('[Ii]f%-[Nn]one%-[Mm]atch:%s*(%S+)') == etag then
      respond(sock, '304 Not Modified', 'application/json', '', { ETag = etag })
    else
      respond(sock, '200 OK', 'application/json', self.data, { ETag = etag })
    end
  elseif method == 'GET' and target == '/highlight' then
    respond(sock, '200 OK', 'application/json', self.highlight or 'null')
  elseif method == 'POST' and target == '/click' then
    respond(sock, '204 No Content', 'text/plain', '')
    vim.schedule(function()
      local ok, msg = pcall(vim.json.decode, body)
      if ok and type(msg) == 'table' then self.on_click(msg) end
    end)
  else
    respond(sock, '404 Not Found', 'text/plain', 'not found')
  end
end

--- New toolpath data (a JSON string): the page picks it up on its next poll.
function S:set_data(json)
  self.data = json
  self.version = self.version + 1
end

--- The element at `file`:`line` (0-based) is under the cursor.
function S:set_highlight(file, line)
  self.seq = self.seq + 1
  self.highlight = vim.json.encode({ seq = self.seq, file = file, line = line })
end

function S:stop()
  if self.server and not self.server:is_closing() then self.server:close() end
end

return S
