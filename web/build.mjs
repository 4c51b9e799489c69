// Bundles the report viewer (src/report.js with three.js and uPlot) into one script and one
// style sheet: node build.mjs OUT_DIR NODE_MODULES_DIR
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const [outDir, nodeModules] = process.argv.slice(2);
if (!outDir || !nodeModules) {
  console.error('usage: node build.mjs OUT_DIR NODE_MODULES_DIR');
  process.exit(2);
}
// esbuild lives in the build tree's node_modules, not beside this file.
const { build } = createRequire(path.join(path.resolve(nodeModules), 'index.js'))('esbuild');
await build({
  entryPoints: [path.join(here, 'src', 'report.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  target: ['es2020'],
  legalComments: 'inline',
  nodePaths: [path.resolve(nodeModules)],
  outfile: path.join(outDir, 'report.js'),
  logLevel: 'warning',
});
