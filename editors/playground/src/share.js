// Share links: the files as JSON, deflate-raw compressed (CompressionStream), base64url in
// the URL's fragment (never sent to a server, not even the page's own).
const PREFIX = 'v1.';

async function pipe(bytes, stream) {
  const s = new Blob([bytes]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(s).arrayBuffer());
}

function base64url(bytes) {
  let bin = '';
  for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(bin).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function unbase64url(text) {
  const bin = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  return Uint8Array.from(bin, (c) => c.charCodeAt(0));
}

/** `{files: {name: text}, active}` → the fragment's text. */
export async function encodeShare(state) {
  const json = new TextEncoder().encode(JSON.stringify(state));
  return PREFIX + base64url(await pipe(json, new CompressionStream('deflate-raw')));
}

/** The fragment's text → the state, or `null` when it is no share link. Throws on a broken one. */
export async function decodeShare(fragment) {
  if (!fragment.startsWith(PREFIX)) return null;
  const json = await pipe(unbase64url(fragment.slice(PREFIX.length)), new DecompressionStream('deflate-raw'));
  const state = JSON.parse(new TextDecoder().decode(json));
  if (!state || typeof state.files !== 'object') throw new Error('no files');
  for (const [k, v] of Object.entries(state.files)) {
    if (typeof v !== 'string' || !/^[^/\\]+$/.test(k)) throw new Error(`bad file ${k}`);
  }
  return state;
}
