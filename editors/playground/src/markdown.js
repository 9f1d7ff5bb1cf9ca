// The hover's Markdown as HTML (marked). What a share link brings in (path names, comments)
// ends up in hovers: raw HTML is shown as text, links and images as their text.
import { Marked } from 'marked';

const esc = (s) => s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
const md = new Marked({ gfm: true, breaks: true });
md.use({
  renderer: {
    html(token) { return esc(token.text || token.raw || ''); },
    link(token) { return this.parser.parseInline(token.tokens); },
    image(token) { return esc(token.text || ''); },
  },
});

export function markdownToHtml(text) {
  return md.parse(text, { async: false });
}
