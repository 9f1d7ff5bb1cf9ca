// The page's words in English and German: the one source for every label, title and line the
// viewer shows (template.html names them with data-t, data-t-title and data-t-label; viewer.js
// calls `t`). The language is the data's `lang` (the settings' `lang`, as millpath's messages
// and statistics), else the host's (`setLang`), else the browser's.
export const WORDS = {
  en: {
    title: 'toolpath',
    top: 'Top', topTitle: 'view from above (X right, Y up)',
    front: 'Front', frontTitle: 'view from the front (−Y)',
    side: 'Side', sideTitle: 'view from the right (+X)',
    iso: 'Iso', isoTitle: 'isometric view',
    colour: 'colour', byDepth: 'by depth', byKind: 'by kind', byFeed: 'by feed',
    cutPart: 'cut part', cutPartTitle: 'the stock after the program, cut as the tool moves during playback',
    toolWidth: 'tool width', toolWidthTitle: 'cuts drawn with the tool diameter O (see the webs from the top)',
    grid: (step) => `grid ${step} mm`,
    legend: 'legend · statistics',
    playTitle: 'play / pause (space)',
    speed: 'speed',
    programTime: 'program time',
    hint: 'Hover or click a move to see the element it comes from and its G-code line.',
    noneYet: 'No toolpath yet.',
    none: 'No toolpath',
    kinds: { mill: 'mill', mark: 'mark', bars: 'bars', drill: 'drill', helix: 'helix', rapid: 'rapid', probe: 'probe' },
    cut: (nx, ny, cell, top) => `cut part ${nx}×${ny} of ${cell} mm  Z ${top}`,
    coarsened: 'coarsened',
    finalSteps: 'playback in final steps',
    surface: (n, min) => `surface ${n} Z ${min}`,
    heightMap: (n, top) => `height map ${n} probe points at the top ${top} mm (not measured)`,
    clamps: (n) => `clamps ${n}`,
    intoClamp: (n) => `${n} move${n > 1 ? 's' : ''} into a clamp`,
    noClampTouched: 'no move touches them',
    tool: (d) => `tool Ø ${d} mm`,
    stock: (top) => `stock top ${top} mm`,
    rapidFeed: 'rapid',
    line: 'line',
    move: (i, n, kind) => `move ${i}/${n} ${kind}`,
    noSource: '(no source element)',
    gcodeLine: (l) => `G-code line ${l}`,
    runsIntoClamp: (names) => `runs into clamp ${names}`,
    moves: (n) => `${n} moves`,
  },
  de: {
    title: 'Werkzeugweg',
    top: 'Oben', topTitle: 'Ansicht von oben (X nach rechts, Y nach oben)',
    front: 'Vorne', frontTitle: 'Ansicht von vorn (−Y)',
    side: 'Seite', sideTitle: 'Ansicht von rechts (+X)',
    iso: 'Iso', isoTitle: 'isometrische Ansicht',
    colour: 'Farbe', byDepth: 'nach Tiefe', byKind: 'nach Art', byFeed: 'nach Vorschub',
    cutPart: 'gefrästes Teil', cutPartTitle: 'das Rohteil nach dem Programm, gefräst, während das Werkzeug bei der Wiedergabe fährt',
    toolWidth: 'Werkzeugbreite', toolWidthTitle: 'Schnitte in der Breite des Werkzeugdurchmessers O (die Stege sind von oben zu sehen)',
    grid: (step) => `Raster ${step} mm`,
    legend: 'Legende · Statistik',
    playTitle: 'Abspielen / Pause (Leertaste)',
    speed: 'Tempo',
    programTime: 'Programmzeit',
    hint: 'Eine Bewegung berühren oder anklicken: das Element, aus dem sie stammt, und ihre G-Code-Zeile.',
    noneYet: 'Noch kein Werkzeugweg.',
    none: 'Kein Werkzeugweg',
    // the elements' keywords stay (they are the language's); the two kinds without one are words
    kinds: { mill: 'mill', mark: 'mark', bars: 'bars', drill: 'drill', helix: 'helix', rapid: 'Eilgang', probe: 'Antasten' },
    cut: (nx, ny, cell, top) => `gefrästes Teil ${nx}×${ny} zu ${cell} mm  Z ${top}`,
    coarsened: 'vergröbert',
    finalSteps: 'Wiedergabe in Endschritten',
    surface: (n, min) => `Oberfläche ${n} Z ${min}`,
    heightMap: (n, top) => `Höhenkarte ${n} Antastpunkte auf der Oberseite ${top} mm (nicht gemessen)`,
    clamps: (n) => `Spannpratzen ${n}`,
    intoClamp: (n) => `${n} ${n > 1 ? 'Bewegungen' : 'Bewegung'} in eine Spannpratze`,
    noClampTouched: 'keine Bewegung berührt sie',
    tool: (d) => `Werkzeug Ø ${d} mm`,
    stock: (top) => `Rohteil oben ${top} mm`,
    rapidFeed: 'Eilgang',
    line: 'Zeile',
    move: (i, n, kind) => `Bewegung ${i}/${n} ${kind}`,
    noSource: '(kein Quellelement)',
    gcodeLine: (l) => `G-Code-Zeile ${l}`,
    runsIntoClamp: (names) => `fährt in die Spannpratze ${names}`,
    moves: (n) => `${n} Bewegungen`,
  },
};

/// `de`, `de-DE`, `de_AT` … are German, everything else English (as millpath's `lang`).
export function langOf(name) {
  return /^de/i.test(String(name || '')) ? 'de' : 'en';
}

let current = 'en';
export function setCurrent(lang) { current = langOf(lang); return current; }
export function currentLang() { return current; }

/// The word `key` in the current language; a function word gets `args`.
export function t(key, ...args) {
  const w = WORDS[current][key] ?? WORDS.en[key];
  return typeof w === 'function' ? w(...args) : w;
}

/// The template's words: data-t (text), data-t-title (title), data-t-label (aria-label).
export function translatePage(root = document) {
  for (const el of root.querySelectorAll('[data-t]')) el.textContent = t(el.dataset.t);
  for (const el of root.querySelectorAll('[data-t-title]')) el.title = t(el.dataset.tTitle);
  for (const el of root.querySelectorAll('[data-t-label]')) el.setAttribute('aria-label', t(el.dataset.tLabel));
  document.documentElement.lang = current;
}
