#!/usr/bin/env node
// The Rust half of the `imports` check (issue 34): no import circles between the files of
// src/. Reads the module tree from src/lib.rs (`mod x;` and `#[path]`, which declare files
// and are not imports), then every `use` and every inline path (`crate::`, `super::`,
// `self::`, or a name a `use` or a child module binds) of each file, comments and strings
// left out. A path is resolved to the file that defines the name it reaches: through
// `use` bindings (a `pub use` in a mod.rs re-exporting its children is followed to the
// child, so the re-exporting file is no part of the edge) and globs. A file depends on
// another if it uses a name defined there; a `use` whose name the file never mentions (a
// re-export) is no dependency, unless it names a trait (its methods are called unnamed).
// Each circle is printed as a chain of files, each step with the line that makes it, and
// the exit code is 1.
//
//   node scripts/check-cycles.mjs [SRC]     SRC defaults to src (of the repository)
//   node scripts/check-cycles.mjs --self-test
//   node scripts/check-cycles.mjs --edges [SRC]   every dependency found, with its line
//
// --self-test runs the check on a small crate written to a temporary folder, with a circle
// it must find and re-exports it must not mistake for one.
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, relative, resolve } from "node:path";
import process from "node:process";

const root = resolve(import.meta.dirname, "..");

/** Tokens of Rust source: identifiers, strings (for `#[path]`), `::` and single punctuation. */
function tokenize(text) {
  const tokens = [];
  const patterns = [
    ["space", /\s+/y],
    ["comment", /\/\/[^\n]*/y],
    ["rawstr", /[bc]?r(#*)"/y],
    ["str", /[bc]?"(?:\\[\s\S]|[^"\\])*"/y],
    ["char", /b?'(?:\\(?:u\{[0-9a-fA-F]+\}|x[0-9a-fA-F]{2}|.)|[^\\'\n])'/y],
    ["lifetime", /'[A-Za-z_][A-Za-z0-9_]*/y],
    ["ident", /(?:r#)?[A-Za-z_][A-Za-z0-9_]*/y],
    ["number", /[0-9][0-9A-Za-z_]*/y],
    ["path", /::/y],
  ];
  let i = 0;
  let line = 1;
  const advance = (to) => {
    for (let k = i; k < to; k++) if (text.charCodeAt(k) === 10) line++;
    i = to;
  };
  outer: while (i < text.length) {
    if (text.startsWith("/*", i)) {
      let depth = 0;
      let k = i;
      do {
        if (text.startsWith("/*", k) || text.startsWith("*/", k)) {
          depth += text[k] === "/" ? 1 : -1;
          k += 2;
        } else k++;
      } while (depth > 0 && k < text.length);
      advance(k);
      continue;
    }
    for (const [kind, re] of patterns) {
      re.lastIndex = i;
      const m = re.exec(text);
      if (!m) continue;
      if (kind === "rawstr") {
        const close = '"' + m[1];
        const end = text.indexOf(close, re.lastIndex);
        const to = end < 0 ? text.length : end + close.length;
        tokens.push({ kind: "str", value: text.slice(re.lastIndex, end < 0 ? to : end), line });
        advance(to);
        continue outer;
      }
      if (kind === "str") tokens.push({ kind, value: m[0].slice(m[0].indexOf('"') + 1, -1), line });
      else if (kind === "ident") tokens.push({ kind, value: m[0].replace(/^r#/, ""), line });
      else if (kind === "path") tokens.push({ kind: "punct", value: "::", line });
      advance(re.lastIndex);
      continue outer;
    }
    tokens.push({ kind: "punct", value: text[i], line });
    advance(i + 1);
  }
  return tokens;
}

const ITEM_KEYWORDS = new Set(["fn", "struct", "enum", "union", "trait", "type", "const", "static"]);

/** A module: a file, or an inline `mod x { }` inside one. */
function newModule(path, file, inline) {
  return {
    path,
    file,
    inline,
    children: new Map(),
    items: new Map(),
    bindings: new Map(),
    globs: [],
    paths: [],
    idents: new Set(),
  };
}

/**
 * Reads one file into `module` (and its inline modules), adding to `modules` (by path) and
 * returning the child files to read: [{ name, file }].
 */
function readModuleFile(module, modules, dirForChildren) {
  const tokens = tokenize(readFileSync(module.file, "utf8"));
  const childFiles = [];
  // Each scope: the module and the brace depth its items sit at.
  const scopes = [{ module, depth: 0, dir: dirForChildren }];
  let depth = 0;
  let pendingPath = null;
  let t = 0;
  const at = (k) => tokens[k] ?? { kind: "eof", value: "" };
  while (t < tokens.length) {
    const scope = scopes[scopes.length - 1];
    const tok = tokens[t];
    const atItemLevel = depth === scope.depth;
    if (tok.value === "#" && (at(t + 1).value === "[" || (at(t + 1).value === "!" && at(t + 2).value === "["))) {
      // An attribute: skipped, except `#[path = "..."]` for the next `mod`.
      let k = at(t + 1).value === "[" ? t + 1 : t + 2;
      if (at(k + 1).value === "path" && at(k + 2).value === "=" && at(k + 3).kind === "str")
        pendingPath = at(k + 3).value;
      let nest = 0;
      do {
        if (at(k).value === "[") nest++;
        else if (at(k).value === "]") nest--;
        k++;
      } while (nest > 0 && k < tokens.length);
      t = k;
      continue;
    }
    if (tok.value === "{") {
      depth++;
      t++;
      continue;
    }
    if (tok.value === "}") {
      depth--;
      if (scopes.length > 1 && depth === scope.depth - 1) scopes.pop();
      t++;
      continue;
    }
    if (
      tok.kind === "ident" &&
      tok.value === "use" &&
      (at(t + 1).kind === "ident" || at(t + 1).value === "{" || at(t + 1).value === "::")
    ) {
      // `pub use` (or `pub(crate) use`) re-exports; any `use` binds names for this scope.
      const end = parseUse(tokens, t + 1, scope.module, isPublic(tokens, t));
      t = end + 1;
      continue;
    }
    if (atItemLevel && tok.kind === "ident" && tok.value === "mod" && at(t + 1).kind === "ident") {
      const name = at(t + 1).value;
      if (at(t + 2).value === ";") {
        const file = pendingPath ? join(dirname(module.file), pendingPath) : null;
        childFiles.push({ name, file, dir: scope.dir, parent: scope.module });
        t += 3;
      } else if (at(t + 2).value === "{") {
        const child = newModule([...scope.module.path, name], module.file, true);
        scope.module.children.set(name, child);
        modules.set(child.path.join("::"), child);
        scopes.push({ module: child, depth: depth + 1, dir: join(scope.dir, name) });
        depth++;
        t += 3;
      } else t++;
      pendingPath = null;
      continue;
    }
    if (atItemLevel && tok.kind === "ident") {
      let kind = null;
      let name = null;
      if (tok.value === "macro_rules" && at(t + 1).value === "!" && at(t + 2).kind === "ident") {
        kind = "macro";
        name = at(t + 2).value;
      } else if (ITEM_KEYWORDS.has(tok.value) && at(t + 1).kind === "ident") {
        kind = tok.value;
        name = at(t + 1).value;
        if (kind === "static" && name === "mut") name = at(t + 2).value;
        if ((kind === "const" && name === "fn") || (kind === "union" && at(t + 2).value === "::")) kind = null;
      }
      if (kind && name && name !== "_" && !scope.module.items.has(name)) scope.module.items.set(name, kind);
    }
    if (tok.kind === "ident" && at(t - 1).value !== "::" && at(t + 1).value === "::") {
      // A path in the code (`$crate::` included): its segments up to the first that is not a name.
      const start = t;
      const segments = [];
      let k = t;
      while (at(k).kind === "ident") {
        segments.push(at(k).value);
        if (at(k + 1).value !== "::" || at(k + 2).kind !== "ident") break;
        k += 2;
      }
      if (segments.length > 1) scope.module.paths.push({ segments, line: tokens[start].line });
      for (const s of segments) scope.module.idents.add(s);
      t = k + 1;
      continue;
    }
    if (tok.kind === "ident") scope.module.idents.add(tok.value);
    t++;
  }
  return childFiles;
}

/** Whether the `use` at token `t` is preceded by `pub` or `pub(...)`. */
function isPublic(tokens, t) {
  let k = t - 1;
  if (tokens[k]?.value === ")") {
    while (k > 0 && tokens[k].value !== "(") k--;
    k--;
  }
  return tokens[k]?.value === "pub";
}

/** Parses a use tree from token `t` to its `;`, adding bindings and globs to `module`. */
function parseUse(tokens, t, module, exported) {
  const line = tokens[t].line;
  const tree = (k, prefix) => {
    const path = [...prefix];
    for (;;) {
      const tok = tokens[k];
      if (tok.value === "::") k++;
      else if (tok.value === "{") {
        k++;
        while (tokens[k].value !== "}") {
          k = tree(k, path);
          if (tokens[k].value === ",") k++;
        }
        return k + 1;
      } else if (tok.value === "*") {
        module.globs.push({ path, line });
        return k + 1;
      } else if (tok.kind === "ident") {
        if (tok.value === "self" && path.length > 0 && prefix.length === path.length) {
          // `a::b::{self, ...}` binds `b`.
        } else path.push(tok.value);
        k++;
        if (tokens[k].value !== "::") {
          let alias = path[path.length - 1];
          if (tokens[k].value === "as") {
            alias = tokens[k + 1].value;
            k += 2;
          }
          if (path.length > 0)
            module.bindings.set(alias === "_" ? `_${module.bindings.size}` : alias, {
              path,
              line,
              exported,
              anonymous: alias === "_",
            });
          return k;
        }
      } else return k + 1;
    }
  };
  let k = t;
  while (k < tokens.length && tokens[k].value !== ";") k = tree(k, []);
  return k;
}

/** Reads the crate from `lib.rs` down: every module by its path ("crate::a::b"). */
function readCrate(src) {
  const modules = new Map();
  const lib = newModule(["crate"], join(src, "lib.rs"), false);
  modules.set("crate", lib);
  const queue = [{ module: lib, dir: src }];
  while (queue.length > 0) {
    const { module, dir } = queue.shift();
    for (const { name, file, dir: childDir, parent } of readModuleFile(module, modules, dir)) {
      const flat = join(childDir, `${name}.rs`);
      const path = file ?? (exists(flat) ? flat : join(childDir, name, "mod.rs"));
      if (!exists(path)) continue;
      // A mod.rs holds its children beside it; a.rs holds them in a/.
      const nextDir = path.endsWith("mod.rs") ? dirname(path) : path.slice(0, -".rs".length);
      const child = newModule([...parent.path, name], path, false);
      parent.children.set(name, child);
      modules.set(child.path.join("::"), child);
      queue.push({ module: child, dir: nextDir });
    }
  }
  return modules;
}

function exists(path) {
  try {
    readFileSync(path);
    return true;
  } catch {
    return false;
  }
}

/** The absolute path (from "crate") that `segments`, written in `module`, names; or null (another crate). */
function absolute(segments, module, modules, depth = 0) {
  if (!segments || depth > 32) return null;
  const [first, ...rest] = segments;
  if (first === "crate") return ["crate", ...rest];
  if (first === "self") return [...module.path, ...rest];
  if (first === "super") {
    let base = module.path;
    let k = 0;
    while (segments[k] === "super") {
      base = base.slice(0, -1);
      k++;
    }
    return [...base, ...segments.slice(k)];
  }
  if (module.children.has(first) || module.items.has(first)) return [...module.path, ...segments];
  const binding = module.bindings.get(first);
  if (binding) {
    const target = absolute(binding.path, module, modules, depth + 1);
    return target && [...target, ...rest];
  }
  return null;
}

/**
 * Where the absolute path `path` leads: { module } for a module, { file, kind } for a name
 * (the file that defines it, re-exports followed), or null.
 */
function locate(path, modules, seen = 0) {
  if (!path || path[0] !== "crate" || seen > 32) return null;
  let module = modules.get("crate");
  let k = 1;
  while (k < path.length && module.children.has(path[k])) module = module.children.get(path[k++]);
  if (k === path.length) return { module };
  const name = path[k];
  if (module.items.has(name)) return { file: module.file, kind: module.items.get(name) };
  const binding = module.bindings.get(name);
  if (binding) return locate(concat(absolute(binding.path, module, modules), path.slice(k + 1)), modules, seen + 1);
  for (const glob of module.globs) {
    const target = locate(absolute(glob.path, module, modules), modules, seen + 1);
    const inner = target?.module;
    if (inner && inner !== module && (inner.items.has(name) || inner.bindings.has(name)))
      return locate([...inner.path, ...path.slice(k)], modules, seen + 1);
  }
  // Not found (made by a macro, say): the module's own file.
  return { file: module.file, kind: null };
}

const concat = (a, b) => (a ? [...a, ...b] : null);

/** Edges between files: Map file -> Map file -> [evidence]. */
function fileEdges(modules) {
  const edges = new Map();
  const show = (file) => relative(process.cwd(), file) || file;
  const add = (from, to, line, what) => {
    if (!to || from === to) return;
    if (!edges.has(from)) edges.set(from, new Map());
    const out = edges.get(from);
    if (!out.has(to)) out.set(to, []);
    out.get(to).push(`${show(from)}:${line} ${what}`);
  };
  for (const module of modules.values()) {
    for (const [alias, binding] of module.bindings) {
      const target = locate(absolute(binding.path, module, modules), modules);
      if (!target || target.module) continue;
      // A trait's methods are called without its name, but a re-exported trait is only passed on.
      const trait = target.kind === "trait" && !binding.exported;
      const mentioned = module.idents.has(alias) || binding.anonymous || trait;
      if (mentioned) add(module.file, target.file, binding.line, `use ${binding.path.join("::")}`);
    }
    for (const glob of module.globs) {
      const target = locate(absolute(glob.path, module, modules), modules)?.module;
      if (!target) continue;
      for (const name of module.idents) {
        if (!target.items.has(name) && !target.bindings.has(name)) continue;
        const found = locate([...target.path, name], modules);
        if (found?.file) add(module.file, found.file, glob.line, `use ${glob.path.join("::")}::* (${name})`);
      }
    }
    for (const { segments, line } of module.paths) {
      const target = locate(absolute(segments, module, modules), modules);
      if (target?.file) add(module.file, target.file, line, segments.join("::"));
    }
  }
  return edges;
}

/** Strongly connected components of more than one file (Tarjan). */
function components(edges) {
  const index = new Map();
  const low = new Map();
  const stack = [];
  const onStack = new Set();
  const found = [];
  let next = 0;
  const visit = (v) => {
    index.set(v, next);
    low.set(v, next++);
    stack.push(v);
    onStack.add(v);
    for (const w of edges.get(v)?.keys() ?? []) {
      if (!index.has(w)) {
        visit(w);
        low.set(v, Math.min(low.get(v), low.get(w)));
      } else if (onStack.has(w)) low.set(v, Math.min(low.get(v), index.get(w)));
    }
    if (low.get(v) === index.get(v)) {
      const component = [];
      let w;
      do {
        w = stack.pop();
        onStack.delete(w);
        component.push(w);
      } while (w !== v);
      if (component.length > 1) found.push(component.sort());
    }
  };
  for (const v of [...edges.keys()].sort()) if (!index.has(v)) visit(v);
  return found;
}

/** The shortest circle through `start` inside `members` (breadth first), as files. */
function shortestCircle(start, members, edges) {
  const previous = new Map([[start, null]]);
  const queue = [start];
  while (queue.length > 0) {
    const v = queue.shift();
    for (const w of [...(edges.get(v)?.keys() ?? [])].sort()) {
      if (!members.has(w)) continue;
      if (w === start) {
        const chain = [v];
        while (previous.get(chain[0]) !== null) chain.unshift(previous.get(chain[0]));
        return [...chain, start];
      }
      if (!previous.has(w)) {
        previous.set(w, v);
        queue.push(w);
      }
    }
  }
  return null;
}

/** The circles of the crate in `src`: for each tangle of files, the shortest circle through each. */
function circles(src) {
  const modules = readCrate(src);
  const edges = fileEdges(modules);
  const result = [];
  for (const component of components(edges)) {
    const members = new Set(component);
    const seen = new Set();
    const chains = [];
    for (const file of component) {
      const chain = shortestCircle(file, members, edges);
      if (!chain) continue;
      // The same circle from another start: rotate it to begin at its smallest file.
      const ring = chain.slice(0, -1);
      const first = ring.indexOf([...ring].sort()[0]);
      const key = [...ring.slice(first), ...ring.slice(0, first)].join(" ");
      if (seen.has(key)) continue;
      seen.add(key);
      chains.push(chain);
    }
    result.push({ files: component, chains });
  }
  return { result, edges };
}

function report(src) {
  const { result, edges } = circles(src);
  const show = (file) => relative(process.cwd(), file) || file;
  for (const { files, chains } of result) {
    console.log(`imports: ${files.length} files in a circle: ${files.map(show).join(", ")}`);
    for (const chain of chains) {
      console.log(`  ${chain.map(show).join(" → ")}`);
      for (let k = 0; k + 1 < chain.length; k++) console.log(`      ${edges.get(chain[k]).get(chain[k + 1])[0]}`);
    }
  }
  if (result.length === 0) console.log(`imports: no circles among the Rust files of ${show(src)}`);
  return result;
}

/** A crate with one circle (a.rs, b.rs) and one between a mod.rs and its child, and re-exports that are none. */
const FIXTURE = {
  "lib.rs": `//! Doc: crate::a::f and crate::b::g in comments are not imports.
mod a;
mod b;
pub mod c;
mod d;
pub mod e;
pub use c::Y;
`,
  "a.rs": `use crate::b::g;
/// [\`crate::b::g\`]
pub fn f() -> u32 {
    g()
}
`,
  "b.rs": `pub fn g() -> u32 {
    if false { crate::a::f() } else { 1 }
}
`,
  // A mod.rs re-exporting its children: no circle. y.rs takes X through the re-export
  // (from x.rs, not from the mod.rs, which calls into y.rs); w.rs uses the mod.rs's own
  // function, and the mod.rs only passes w.rs's on.
  "c/mod.rs": `mod w;
mod x;
mod y;
pub use w::twice;
pub use x::X;
pub use y::Y;
pub fn helper() -> u32 { 2 }
pub fn make() -> Y { y::new() }
`,
  "c/w.rs": `use super::helper;
pub fn twice() -> u32 { 2 * helper() }
`,
  "c/x.rs": `pub struct X;
`,
  "c/y.rs": `use super::X;
pub struct Y(pub X);
pub fn new() -> Y { Y(X) }
`,
  // A string and a child file through #[path]; the child uses its parent: no circle.
  "d.rs": `pub const S: &str = "crate::e::h";
pub fn k() {}
#[path = "d_tests.rs"]
mod tests;
`,
  "d_tests.rs": `use super::*;
fn t() { k(); let _ = S; }
`,
  // A real circle between a mod.rs and its child: the child uses a function of the
  // parent, and the parent calls the child's (through the child module's name).
  "e/mod.rs": `mod inner;
pub fn h() -> u32 { 1 }
pub fn twice() -> u32 { inner::call() * 2 }
`,
  "e/inner.rs": `use super::h;
pub(super) fn call() -> u32 { h() }
`,
};

function selfTest() {
  const dir = mkdtempSync(join(tmpdir(), "akap-cycles-"));
  try {
    for (const [name, text] of Object.entries(FIXTURE)) {
      mkdirSync(dirname(join(dir, name)), { recursive: true });
      writeFileSync(join(dir, name), text);
    }
    const { result } = circles(dir);
    const found = result.map(({ chains }) => chains.map((c) => c.map((f) => relative(dir, f)).join(" → ")).join(" | "));
    const expected = ["a.rs → b.rs → a.rs", "e/inner.rs → e/mod.rs → e/inner.rs"];
    found.sort();
    const ok = found.length === expected.length && expected.every((e, k) => found[k] === e);
    if (!ok) {
      console.log(
        `imports: self-test FAILED: expected\n  ${expected.join("\n  ")}\nfound\n  ${found.join("\n  ") || "(none)"}`,
      );
      return false;
    }
    console.log(`imports: self-test passed (finds ${expected.length} circles, no false one through re-exports)`);
    return true;
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

const args = process.argv.slice(2);
if (args[0] === "--self-test") process.exit(selfTest() ? 0 : 1);
if (args[0] === "--edges") {
  const edges = fileEdges(readCrate(resolve(args[1] ?? join(root, "src"))));
  for (const out of edges.values()) for (const evidence of out.values()) console.log(evidence[0]);
  process.exit(0);
}
const src = resolve(args[0] ?? join(root, "src"));
process.exit(report(src).length === 0 ? 0 : 1);
