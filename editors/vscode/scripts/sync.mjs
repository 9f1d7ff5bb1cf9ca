// Copies the shared pieces into the extension: the TextMate grammar and the toolpath page.
import { copyFileSync, mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
const here = dirname(fileURLToPath(import.meta.url));
const root = join(here, '..');
mkdirSync(join(root, 'syntaxes'), { recursive: true });
mkdirSync(join(root, 'media'), { recursive: true });
copyFileSync(join(root, '../../grammar/millpath.tmLanguage.json'), join(root, 'syntaxes/millpath.tmLanguage.json'));
copyFileSync(join(root, '../toolpath/toolpath.html'), join(root, 'media/toolpath.html'));
