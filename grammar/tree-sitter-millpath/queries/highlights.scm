; MillPath highlighting
(comment) @comment
(kind) @keyword
(path "path" @keyword)
(path name: (_) @type)
(arc ["arc" "from" "to"] @keyword)
(turn) @keyword
(number) @number
(radius) @number
(diameter) @number
(parameter) @string.special
(string) @string
["(" ")" "{" "}"] @punctuation.bracket
["," ] @punctuation.delimiter
"->" @operator
