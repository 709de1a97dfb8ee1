// Moved to lab/posing/bench-app.mjs (`npm run bench:app`); this forward keeps
// `node scripts/bench-app.mjs ...` working while issue 34's measurements run. Remove it then.
await import("../lab/posing/bench-app.mjs");
