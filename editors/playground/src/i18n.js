// The page's own words in English and German (the compiler's messages come from the wasm,
// in the language it is given).
export const WORDS = {
  en: {
    files: 'Files', newFile: '+ file', newFilePrompt: 'Name of the new file (.mpath):', format: 'Format',
    openDxf: 'Open DXF…', download: 'Download', downloadMpath: '.mpath', downloadDxf: '.dxf', downloadGcode: 'G-code',
    share: 'Share link', copied: 'Link copied to the clipboard', shareHint: 'The link carries the files (compressed); nothing is uploaded.',
    gcode: 'G-code', toolpath: 'Toolpath', settings: 'millpath.toml', noGcode: 'No G-code: ',
    dropHint: 'Drop a .dxf drawing (or an .mpath file) anywhere to open it as text.',
    loading: 'Loading the compiler…', problems: (e, w) => `${e} errors, ${w} warnings`,
    removeFile: 'Remove this file', offline: 'Everything runs in this page: nothing is sent anywhere.',
    badShare: 'This share link cannot be read: ', dxfOpened: (n) => `${n} opened as text`,
    post: 'Post:', postOfToml: 'as millpath.toml says',
  },
  de: {
    files: 'Dateien', newFile: '+ Datei', newFilePrompt: 'Name der neuen Datei (.mpath):', format: 'Formatieren',
    openDxf: 'DXF öffnen…', download: 'Herunterladen', downloadMpath: '.mpath', downloadDxf: '.dxf', downloadGcode: 'G-Code',
    share: 'Link teilen', copied: 'Link in die Zwischenablage kopiert', shareHint: 'Der Link trägt die Dateien (komprimiert); nichts wird hochgeladen.',
    gcode: 'G-Code', toolpath: 'Werkzeugweg', settings: 'millpath.toml', noGcode: 'Kein G-Code: ',
    dropHint: 'Eine .dxf-Zeichnung (oder .mpath-Datei) hier ablegen, um sie als Text zu öffnen.',
    loading: 'Der Compiler wird geladen…', problems: (e, w) => `${e} Fehler, ${w} Warnungen`,
    removeFile: 'Diese Datei entfernen', offline: 'Alles läuft in dieser Seite: nichts wird irgendwohin gesendet.',
    badShare: 'Dieser Link ist nicht lesbar: ', dxfOpened: (n) => `${n} als Text geöffnet`,
    post: 'Post:', postOfToml: 'wie millpath.toml sagt',
  },
};
