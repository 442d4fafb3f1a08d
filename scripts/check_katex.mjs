// Usage: cargo doc -p flexure --no-deps --document-private-items && node scripts/check_katex.mjs
// with KaTeX at the version scripts/package.json pins: `npm ci --prefix scripts` installs it
// beside this script (scripts/node_modules, ignored by git), or point NODE_PATH at a
// node_modules elsewhere (CI: `npm ci` in a temporary copy of scripts/package*.json).
//
// Checks the maths of flexure's rustdoc the way the KaTeX header
// (crates/flexure/katex-header.html) renders it: every `$…$`/`$$…$$` that
// KaTeX's auto-render would find in the HTML's text nodes must parse with
// `throwOnError: true`, and must equal, character for character (runs of
// white space aside), a formula written in a doc comment of
// crates/flexure/src, because rustdoc's Markdown silently rewrites
// formulas (`\,` to `,`, `\\` to `\`, `'` to `’`, `_…_` to emphasis).
// Every formula of the source must also be found in the HTML (a formula split
// by emphasis or a link is not), and no `$` may be left over in the text.
// Exits 1 on any failure.

import { createRequire } from "node:module";
import { readFileSync, readdirSync, statSync } from "node:fs";
import { join, relative, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const require = createRequire(import.meta.url);
const katex = require("katex");

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const docDir = process.argv[2] ?? join(root, "target/doc/flexure");
const srcDir = process.argv[3] ?? join(root, "crates/flexure/src");

// The header's delimiters, in its order ($$ before $).
const DELIMITERS = [
  { left: "$$", right: "$$", display: true },
  { left: "$", right: "$", display: false },
];

// Auto-render's splitter (katex/contrib/auto-render/splitAtDelimiters.js,
// 0.16.22), restated because that file is not exported by the package.
function findEndOfMath(delimiter, text, startIndex) {
  let index = startIndex;
  let braceLevel = 0;
  while (index < text.length) {
    const character = text[index];
    if (braceLevel <= 0 && text.slice(index, index + delimiter.length) === delimiter) {
      return index;
    } else if (character === "\\") {
      index++;
    } else if (character === "{") {
      braceLevel++;
    } else if (character === "}") {
      braceLevel--;
    }
    index++;
  }
  return -1;
}

// Each part also gets `at`, its offset in the text.
function splitAtDelimiters(text) {
  const data = [];
  let at = 0;
  for (;;) {
    const index = text.search(/(\$\$|\$)/);
    if (index === -1) break;
    if (index > 0) {
      data.push({ type: "text", data: text.slice(0, index), at });
      text = text.slice(index);
      at += index;
    }
    const delim = DELIMITERS.find((d) => text.startsWith(d.left));
    const end = findEndOfMath(delim.right, text, delim.left.length);
    if (end === -1) break;
    data.push({ type: "math", data: text.slice(delim.left.length, end), display: delim.display, at });
    text = text.slice(end + delim.right.length);
    at += end + delim.right.length;
  }
  if (text !== "") data.push({ type: "text", data: text, at });
  return data;
}

function walk(dir, ext) {
  const out = [];
  for (const name of readdirSync(dir).sort()) {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) out.push(...walk(path, ext));
    else if (name.endsWith(ext)) out.push(path);
  }
  return out;
}

const NAMED_ENTITIES = { amp: "&", lt: "<", gt: ">", quot: '"', apos: "'", nbsp: "\u00a0" };
function decodeEntities(text, where) {
  return text.replace(/&(#x[0-9a-fA-F]+|#[0-9]+|[a-zA-Z]+);/g, (whole, body) => {
    if (body[0] === "#") {
      return String.fromCodePoint(body[1] === "x" ? parseInt(body.slice(2), 16) : parseInt(body.slice(1), 10));
    }
    if (body in NAMED_ENTITIES) return NAMED_ENTITIES[body];
    throw new Error(`${where}: unknown HTML entity ${whole}`);
  });
}

// The text nodes of <body> that auto-render visits: those outside its ignored
// tags. Any tag or comment ends a text node.
const IGNORED = new Set(["script", "noscript", "style", "textarea", "pre", "code", "option"]);
function textNodes(html, where) {
  const body = html.indexOf("<body");
  if (body === -1) return [];
  html = html.slice(body);
  const nodes = [];
  let ignoredDepth = 0;
  const token = /<!--[\s\S]*?-->|<(\/?)([a-zA-Z][a-zA-Z0-9-]*)((?:[^>"']|"[^"]*"|'[^']*')*)>|([^<]+)|</g;
  let m;
  while ((m = token.exec(html)) !== null) {
    if (m[4] !== undefined) {
      if (ignoredDepth === 0) nodes.push(decodeEntities(m[4], where));
      continue;
    }
    if (m[2] === undefined) continue; // comment or lone '<'
    const name = m[2].toLowerCase();
    if (name === "script" || name === "style") {
      if (m[1] === "") {
        const close = html.indexOf(`</${name}`, token.lastIndex);
        token.lastIndex = close === -1 ? html.length : close;
      }
      continue;
    }
    if (IGNORED.has(name) && !m[3].trimEnd().endsWith("/")) ignoredDepth += m[1] === "/" ? -1 : 1;
  }
  return nodes;
}

// Formulas written in the doc comments (`///`, `//!`, and files pulled in by
// `#![doc = include_str!(…)]`), outside code blocks, code spans and test
// modules.
function docBlocks(file) {
  const blocks = [];
  let current = null;
  const lines = readFileSync(file, "utf8").split("\n");
  // A `#[cfg(test)]` module's docs are never rendered: skip it, to its
  // closing brace at the module's own indentation.
  let skipUntil = null;
  lines.forEach((line, i) => {
    if (skipUntil !== null) {
      if (line === skipUntil) skipUntil = null;
      return;
    }
    const test = line.match(/^(\s*)#\[cfg\(test\)\]\s*$/);
    if (test && /^\s*(pub(\([^)]*\))?\s+)?mod\s+\w+\s*\{\s*$/.test(lines[i + 1] ?? "")) {
      skipUntil = `${test[1]}}`;
      current = null;
      return;
    }
    const include = line.match(/^\s*#!?\[doc\s*=\s*include_str!\("([^"]+)"\)\]/);
    if (include) {
      blocks.push({ line: i + 1, text: readFileSync(join(dirname(file), include[1]), "utf8") });
    }
    const doc = line.match(/^\s*(\/\/\/|\/\/!)(?!\/)(.*)$/);
    if (doc) {
      const text = doc[2].startsWith(" ") ? doc[2].slice(1) : doc[2];
      if (current && current.kind === doc[1]) current.lines.push(text);
      else {
        current = { kind: doc[1], line: i + 1, lines: [text] };
        blocks.push(current);
      }
    } else if (!include) {
      current = null;
    }
  });
  return blocks.map((b) => ({ line: b.line, text: b.text ?? b.lines.join("\n") }));
}

function stripCode(markdown) {
  let inFence = null;
  const kept = markdown.split("\n").map((line) => {
    const fence = line.match(/^\s{0,3}(`{3,}|~{3,})/);
    if (fence) {
      if (inFence === null) inFence = fence[1];
      else if (fence[1].startsWith(inFence)) inFence = null;
      return "";
    }
    return inFence === null ? line : "";
  });
  // Code spans: a run of n backticks up to the next run of exactly n. Blanked
  // out, newlines kept, so that offsets still give line numbers.
  return kept.join("\n").replace(/(`+)([\s\S]*?[^`])\1(?!`)/g, (span) => span.replace(/[^\n]/g, " "));
}

const normalise = (tex) => tex.replace(/\s+/g, " ").trim();

const failures = [];
const fail = (message) => failures.push(message);

// Source formulas, keyed by their normalised text, with every place written.
const source = new Map();
let written = 0;
for (const file of walk(srcDir, ".rs")) {
  for (const block of docBlocks(file)) {
    const text = stripCode(block.text);
    for (const part of splitAtDelimiters(text)) {
      if (part.type !== "math") continue;
      written++;
      const key = normalise(part.data);
      const line = block.line + (text.slice(0, part.at).match(/\n/g) ?? []).length;
      if (!source.has(key)) source.set(key, { places: [], found: false });
      source.get(key).places.push(`${relative(root, file)}:${line}`);
    }
  }
}

// HTML formulas.
let rendered = 0;
const distinct = new Set();
for (const file of walk(docDir, ".html")) {
  const where = relative(root, file);
  for (const node of textNodes(readFileSync(file, "utf8"), where)) {
    for (const part of splitAtDelimiters(node)) {
      if (part.type === "text") {
        if (part.data.includes("$")) fail(`${where}: a '$' is left over in the text (a formula split by Markdown?): ${JSON.stringify(normalise(part.data).slice(0, 120))}`);
        continue;
      }
      rendered++;
      const key = normalise(part.data);
      distinct.add(key);
      try {
        katex.renderToString(part.data, {
          displayMode: part.display,
          throwOnError: true,
          strict: (code, message) => {
            fail(`${where}: KaTeX strict-mode warning (${code}) in ${JSON.stringify(key)}: ${message}`);
            return "ignore";
          },
        });
      } catch (e) {
        fail(`${where}: KaTeX cannot parse ${JSON.stringify(key)}: ${e.message}`);
      }
      const origin = source.get(key);
      if (origin) origin.found = true;
      else fail(`${where}: ${JSON.stringify(key)} is no formula of the source: Markdown rewrote it`);
    }
  }
}

for (const [key, origin] of source) {
  if (origin.found) continue;
  for (const place of origin.places) {
    fail(`${place}: ${JSON.stringify(key)} is not in the HTML as written (built with --document-private-items?)`);
  }
}

const unique = [...new Set(failures)];
for (const message of unique) console.log(message);
console.log(
  `${written} formulas (${source.size} distinct) in the source, ${rendered} (${distinct.size} distinct) in the HTML; ${unique.length} failures`,
);
process.exit(unique.length === 0 ? 0 : 1);
