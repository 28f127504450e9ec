// Bundles the builder's front end (src/main.js and its imports, three.js among them) with
// esbuild into one folder: index.html, app.js, app.css and the files of public/.
// Usage: node build.mjs [--outdir DIR] [--cpp FILE]
//   --outdir DIR  where the bundle goes (default: dist/ beside this file)
//   --cpp FILE    also writes a C++ source embedding every file of the bundle, implementing
//                 builder/server/assets.h (the plantarch binary serves it; see embed.mjs)
// Nothing is fetched: everything comes from node_modules (npm ci) and this folder.
import { build } from 'esbuild';
import { cp, mkdir, rm, readdir } from 'node:fs/promises';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { writeAssetsCpp } from './embed.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));

function parseArgs(argv) {
  const options = { outdir: path.join(here, 'dist'), cpp: null };
  for (let i = 0; i < argv.length; i++) {
    const flag = argv[i];
    if ((flag === '--outdir' || flag === '--cpp') && i + 1 < argv.length) {
      options[flag.slice(2)] = path.resolve(argv[++i]);
    } else {
      throw new Error(`build.mjs: unknown argument '${flag}' (valid: --outdir DIR, --cpp FILE)`);
    }
  }
  return options;
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  // A fresh folder each time: a file removed from the sources leaves no stale copy behind.
  await rm(options.outdir, { recursive: true, force: true });
  await mkdir(options.outdir, { recursive: true });
  await build({
    entryPoints: { app: path.join(here, 'src/main.js') },
    bundle: true,
    format: 'esm',
    target: ['es2022'],
    minify: true,
    legalComments: 'eof',
    outdir: options.outdir,
    logLevel: 'warning',
  });
  await build({
    entryPoints: { app: path.join(here, 'src/app.css') },
    bundle: true,
    minify: true,
    outdir: options.outdir,
    logLevel: 'warning',
  });
  await cp(path.join(here, 'index.html'), path.join(options.outdir, 'index.html'));
  const publicDir = path.join(here, 'public');
  if (existsSync(publicDir)) {
    for (const name of await readdir(publicDir)) {
      await cp(path.join(publicDir, name), path.join(options.outdir, name), { recursive: true });
    }
  }
  if (options.cpp) await writeAssetsCpp(options.outdir, options.cpp);
}

main().catch((e) => {
  console.error(e.message ?? String(e));
  process.exit(1);
});
