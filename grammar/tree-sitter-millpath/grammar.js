/**
 * Tree-sitter grammar of the MillPath text language (*.mpath). Kept in step with the parser
 * in crates/syntax (a test parses every example with both). See docs/language.md.
 */
module.exports = grammar({
  name: 'millpath',

  extras: $ => [/[ \t\f]/],

  word: $ => $.word,

  rules: {
    source_file: $ => repeat(choice($._newline, $._comment_line, $.path)),

    _newline: $ => /\r?\n/,

    comment: $ => token(seq('#', /[^\r\n]*/)),

    _comment_line: $ => seq($.comment, $._newline),

    path: $ => prec.right(seq(
      'path',
      field('name', choice($.name, $.string)),
      '{',
      optional($.comment),
      $._newline,
      repeat(choice($._newline, $._comment_line, $.element)),
      '}',
      optional($.comment),
      optional($._newline),
    )),

    name: $ => /[^\s(){},#"][^\s(){},"]*/,

    element: $ => seq(
      field('kind', $.kind),
      field('geometry', $._geometry),
      optional($.parameters),
      optional($.comment),
      $._newline,
    ),

    kind: $ => choice(
      'start', 'end', 'turn', 'probe', 'noprobe',
      'mill', 'mark', 'bars', 'sub', 'sweep', 'move', 'skip',
      seq(optional(choice('mark', 'bars')), choice('drill', 'helix')),
      seq('raw', field('linetype', choice($.word, $.string))),
    ),

    _geometry: $ => choice($.point, $.line, $.arc, $.circle),

    point: $ => seq('(', field('x', $.number), ',', field('y', $.number), ')'),

    line: $ => seq(
      field('from', $.point), '->', field('to', $.point),
      optional(seq(field('direction', $.turn), field('center', $.point))),
    ),

    // one token, so that it beats a parameter word `ccw` by length
    turn: $ => token(seq(choice('ccw', 'cw'), /[ \t]+/, 'around')),

    arc: $ => seq(
      'arc',
      field('center', $.point),
      field('radius', $.radius),
      'from', field('start_angle', $.number),
      'to', field('end_angle', $.number),
    ),

    circle: $ => seq(field('center', $.point), field('diameter', $.diameter)),

    radius: $ => token(seq('r', optional(/[ \t]+/), /[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?/)),

    diameter: $ => token(seq('d', optional(/[ \t]+/), /[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?/)),

    number: $ => /[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?/,

    parameters: $ => repeat1(choice($.parameter, $.string)),

    parameter: $ => token(prec(-1, /[^\s#"][^\s]*/)),

    string: $ => /"([^"\\\r\n]|\\.)*"/,

    word: $ => /[^\s(){},#"0-9+\-.][^\s(){},"]*/,
  },
});
