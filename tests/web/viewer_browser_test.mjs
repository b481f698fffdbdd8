// Browser test of the viewer (web/viewer/ served by `hapticctl view`).
//
//   node tests/web/viewer_browser_test.mjs --server-bin build/bin/haptic-server \
//     --hapticctl build/bin/hapticctl --scene-file scenes/probe_on_torus.textproto \
//     --artifacts build/web-test [--chromium /usr/bin/chromium]
//
// Exit 0: passed. Exit 1: failed (the reason on stderr, with the tails of the
// children's logs and the pages' console). Exit 77: skipped, because chromium
// (or the playwright-core npm package: run scripts/setup.sh) is not there or
// cannot be launched; CTest registers it with SKIP_RETURN_CODE 77.
//
// Needs only node and playwright-core (package.json); the browser is
// Debian's /usr/bin/chromium, never one Playwright downloads. Headless
// chromium renders WebGL with SwiftShader (software): --enable-unsafe-swiftshader
// opts in to that (Playwright passes it too, today); as root chromium also
// needs --no-sandbox.
//
// What it does (about 55 s; a watchdog fails it at 240 s):
//   1. launches chromium (skip if it cannot);
//   2. starts haptic-server --listen 127.0.0.1:0 --scene FILE, as
//      scripts/start_server.sh does, and reads "listening on port N" from its log;
//   3. starts `hapticctl view --server 127.0.0.1:N --scene NAME --http 127.0.0.1:0`
//      and reads "viewer on http://127.0.0.1:M/" from its stdout;
//   4. opens two pages (A, B) there; waits for viewerState.connected and frames > 0;
//      the page has taken the ?token= out of its address and came with the
//      security headers (Content-Security-Policy, nosniff);
//   4b. the edge: a page of another origin (a port this test serves)
//      cannot open the bridge's WebSocket even with the token; the page's
//      own origin cannot without it or with a wrong one, and can with it;
//   5. A takes the probe (viewerTest.take), does one real mouse drag on the
//      canvas (posesSent must grow), puts the probe back above its start with
//      viewerTest.moveBy, then lowers it 1 cm at a time until there is a contact,
//      and presses 5 mm further; F frames the camera on the probe and its
//      contact, a few centimetres away instead of the whole scene;
//   6. asserts on A: a contact, highlighted features on both sides, the force
//      and reversing-vector arrows, probe force > 0; on B: the same probe
//      device_p as A (within 1e-6) and a holder for the probe;
//   6b. adds a second tool (hapticctl objects add): page B drives it while
//      A drives the probe, and both pages see both tools where they were put;
//      a tool a device (hapticctl drive) holds shows that device's name as
//      its holder in the pages' tools table;
//      a socket's malformed and unheld messages are counted and move nothing;
//      hapticctl snapshot writes DIR/snapshot.png; a free cube added on
//      the table is drawn where the frames' bodies put it when page A's
//      probe pushes it; a bridge for an unknown
//      scene says so in its page, also after a reload, and runs on; when the server goes away,
//      page A shows it and the bridge runs on;
//   7. saves DIR/viewer-a.png and DIR/viewer-b.png (also when failing), and
//      always stops the server and the bridge.
//
// The page's test interface (web/viewer/): window.viewerState = { connected,
// frames, posesSent, heldTool, contacts: [...], highlighted: { tool_vertices,
// tool_edges, tool_faces, object_vertices, object_edges, object_faces },
// arrows: { force, reversing_vector }, tools: { probe: { device_p: [x,y,z],
// force_magnitude_n, holder } }, bodies: { pebble: { mesh_p: [x,y,z], held,
// touching_tools } } } and window.viewerTest = { take(tool),
// moveBy([dx,dy,dz]) } (metres, world frame, z up).
//
// The demo scene (scenes/probe_on_torus.textproto): the probe, a 2 cm cube,
// starts at (0.1, 0, 0.1), so its bottom face is at z = 0.09; the organ, a
// torus of major radius 0.1 and minor radius 0.04 lying at z = 0.04, has the
// top of its tube under the probe at (0.1, 0, 0.08). So the probe is 1 cm
// above the organ and moving it down (-z) touches it after about 1 cm.

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { parseArgs } from 'node:util';

const TEST_BUDGET_MS = 240_000;  // generous: a loaded machine takes it past twice its time
const SKIP = 77;
// waitUntil re-checks at this interval, not at each animation frame
// (waitForFunction's default): a page behind another gets few frames or
// none, so under load page A, opened first, could miss being connected
// for 20 s.
const kPollMs = 100;

/** A test failure with a message that says it all (no stack trace printed). */
class Failure extends Error {}

// ---- arguments -------------------------------------------------------------

let args;
try {
  ({ values: args } = parseArgs({
    options: {
      'server-bin': { type: 'string' },
      'hapticctl': { type: 'string' },
      'scene-file': { type: 'string' },
      'artifacts': { type: 'string' },
      'chromium': { type: 'string', default: '/usr/bin/chromium' },
    },
  }));
  for (const name of ['server-bin', 'hapticctl', 'scene-file', 'artifacts']) {
    if (!args[name]) throw new Error(`--${name} is required`);
  }
} catch (e) {
  console.error(`viewer_browser_test: ${e.message}`);
  console.error('usage: node viewer_browser_test.mjs --server-bin PATH --hapticctl PATH ' +
                '--scene-file PATH --artifacts DIR [--chromium PATH]');
  process.exit(1);
}

// ---- children, cleanup and exits ------------------------------------------

const children = [];   // {name, proc, log: string[]}
const consoleLines = [];  // the pages' console errors and page errors
let browser = null;
const pages = {};      // a, b
let step = 'starting';
let finishing = false;

function log(message) {
  console.log(`viewer_browser_test: ${message}`);
}

function startChild(name, file, argv) {
  try {
    fs.accessSync(file, fs.constants.X_OK);
  } catch (e) {
    throw new Failure(`${name}: ${file} is not an executable file (${e.code})`);
  }
  const proc = spawn(file, argv, { stdio: ['ignore', 'pipe', 'pipe'] });
  const child = { name, proc, log: [], listeners: [] };
  // Output comes in arbitrary pieces: split each stream into whole lines.
  const lineReader = () => {
    let partial = '';
    return (data) => {
      const lines = (partial + data.toString()).split('\n');
      partial = lines.pop();
      for (const line of lines) {
        if (!line) continue;
        child.log.push(line);
        if (child.log.length > 40) child.log.shift();
        for (const listener of child.listeners) listener(line);
      }
    };
  };
  proc.stdout.on('data', lineReader());
  proc.stderr.on('data', lineReader());
  proc.on('error', (e) => child.log.push(`(${name} could not start: ${e.message})`));
  children.push(child);
  return child;
}

function alive(proc) {
  return proc.exitCode === null && proc.signalCode === null && proc.pid !== undefined;
}

/** Resolves with the first match of `re` in the child's output, or rejects. */
function waitForLine(child, re, timeoutMs) {
  return new Promise((resolve, reject) => {
    const done = (fn, value) => {
      clearTimeout(timer);
      child.listeners = child.listeners.filter((l) => l !== listener);
      child.proc.off('exit', onExit);
      child.proc.off('error', onExit);
      fn(value);
    };
    const listener = (line) => {
      const m = line.match(re);
      if (m) done(resolve, m);
    };
    const onExit = () => done(reject, new Failure(
      `${child.name} ended (exit ${child.proc.exitCode ?? child.proc.signalCode ?? 'error'}) ` +
      `before printing ${re}`));
    const timer = setTimeout(() => done(reject, new Failure(
      `${child.name} did not print ${re} within ${timeoutMs / 1000} s`)), timeoutMs);
    for (const line of child.log) {
      const m = line.match(re);
      if (m) { clearTimeout(timer); resolve(m); return; }
    }
    if (!alive(child.proc)) { onExit(); return; }
    child.listeners.push(listener);
    child.proc.on('exit', onExit);
    child.proc.on('error', onExit);
  });
}

async function stopChildren() {
  await Promise.all(children.map(({ proc }) => new Promise((resolve) => {
    if (!alive(proc)) { resolve(); return; }
    const kill = setTimeout(() => { if (alive(proc)) proc.kill('SIGKILL'); }, 3000);
    proc.once('exit', () => { clearTimeout(kill); resolve(); });
    proc.kill('SIGTERM');
  })));
}

/** Best effort: saves whatever pages there are to the artifacts directory. */
async function saveScreenshots() {
  try {
    fs.mkdirSync(args.artifacts, { recursive: true });
  } catch (e) {
    log(`cannot create ${args.artifacts}: ${e.message}`);
    return;
  }
  for (const [key, page] of Object.entries(pages)) {
    const file = path.join(args.artifacts, `viewer-${key}.png`);
    try {
      await page.screenshot({ path: file, timeout: 5000 });
    } catch (e) {
      log(`screenshot ${file} failed: ${e.message.split('\n')[0]}`);
    }
  }
}

function withTimeout(promise, ms) {
  return Promise.race([promise, new Promise((resolve) => setTimeout(resolve, ms))]);
}

async function finish(code, message) {
  if (finishing) return;
  finishing = true;
  clearTimeout(watchdog);
  if (code === 1) {
    console.error(`viewer_browser_test: FAIL (${step}): ${message}`);
    for (const child of children) {
      if (child.log.length === 0) continue;
      console.error(`--- last lines of ${child.name}:`);
      for (const line of child.log) console.error(`  ${line}`);
    }
    if (consoleLines.length > 0) {
      console.error('--- page console errors:');
      for (const line of consoleLines.slice(-20)) console.error(`  ${line}`);
    }
  } else if (code === SKIP) {
    console.error(`viewer_browser_test: SKIP: ${message}`);
  } else {
    log(message);
  }
  // Screenshots and shutdown get at most 4 s each: the whole test stays under 60 s.
  if (Object.keys(pages).length > 0) await withTimeout(saveScreenshots(), 4000);
  if (browser) await withTimeout(browser.close().catch(() => {}), 4000);
  await withTimeout(stopChildren(), 4000);
  process.exit(code);
}

// Last resort: whatever happens, no child outlives this process.
process.on('exit', () => {
  for (const { proc } of children) if (alive(proc)) proc.kill('SIGKILL');
});
for (const signal of ['SIGINT', 'SIGTERM', 'SIGHUP']) {
  process.on(signal, () => finish(1, `got ${signal}`));
}
process.on('uncaughtException', (e) => finish(1, e.stack || String(e)));
process.on('unhandledRejection', (e) => finish(1, e?.stack || String(e)));

const watchdog = setTimeout(
  () => finish(1, `timed out: the test did not end within ${TEST_BUDGET_MS / 1000} s`),
  TEST_BUDGET_MS);

function check(condition, message) {
  if (!condition) throw new Failure(message);
}

// ---- the page --------------------------------------------------------------

/** Waits until `predicate(arg)` holds in `page`, re-checking every kPollMs. */
const waitUntil = (page, predicate, timeout, arg = null) =>
  page.waitForFunction(predicate, arg, { polling: kPollMs, timeout });

const state = (page) => page.evaluate(() => JSON.parse(JSON.stringify(window.viewerState ?? null)));

/** The numbers of a position, whether [x, y, z] or {x, y, z}. */
function vec3(p) {
  if (Array.isArray(p) && p.length === 3 && p.every(Number.isFinite)) return p;
  if (p && [p.x, p.y, p.z].every(Number.isFinite)) return [p.x, p.y, p.z];
  return null;
}

const probeOf = (s) => s?.tools?.probe;
const devicePOf = (s) => vec3(probeOf(s)?.device_p);
const holderOf = (s) => probeOf(s)?.holder ?? s?.holders?.probe;

function sumKeys(obj, prefix) {
  return Object.entries(obj ?? {})
    .filter(([k, v]) => k.startsWith(prefix) && Number.isFinite(v))
    .reduce((sum, [, v]) => sum + v, 0);
}

function brief(s) {
  const text = JSON.stringify(s);
  return text && text.length > 1500 ? `${text.slice(0, 1500)}...` : text;
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/** Polls the page until the probe's device_p stops changing (or `ms` passes). */
async function settledDeviceP(page, ms) {
  const end = Date.now() + ms;
  let last = devicePOf(await state(page));
  let stableSince = Date.now();
  while (Date.now() < end) {
    await sleep(100);
    const now = devicePOf(await state(page));
    const same = now && last && now.every((v, i) => Math.abs(v - last[i]) < 1e-9);
    if (!same) stableSince = Date.now();
    else if (Date.now() - stableSince >= 300) return now;
    last = now;
  }
  return last;
}

// ---- the test ---------------------------------------------------------------

async function main() {
  const sceneText = fs.readFileSync(args['scene-file'], 'utf8');
  const sceneName = sceneText.match(/^name:\s*"([^"]*)"/m)?.[1] ?? 'probe on torus';
  // The probe's start: 1 cm above the top of the organ's tube (see the header).
  const probeStart = [0.1, 0, 0.1];

  step = 'loading playwright-core';
  let chromium;
  try {
    ({ chromium } = await import('playwright-core'));
  } catch (e) {
    return finish(SKIP, `playwright-core is not installed (run scripts/setup.sh): ${e.message}`);
  }

  step = 'launching chromium';
  if (!fs.existsSync(args.chromium)) {
    return finish(SKIP, `${args.chromium} does not exist (Debian package chromium; run scripts/setup.sh)`);
  }
  const launchArgs = ['--enable-unsafe-swiftshader'];
  if (process.getuid?.() === 0) launchArgs.push('--no-sandbox');
  try {
    browser = await chromium.launch({
      executablePath: args.chromium, headless: true, args: launchArgs, timeout: 15_000,
    });
  } catch (e) {
    return finish(SKIP, `chromium cannot be launched: ${e.message.split('\n').slice(0, 8).join(' | ')}`);
  }

  step = 'starting haptic-server';
  const server = startChild('haptic-server', args['server-bin'],
    ['--listen', '127.0.0.1:0', '--scene', args['scene-file']]);
  const port = Number((await waitForLine(server, /listening on port (\d+)/, 15_000))[1]);
  log(`haptic-server on 127.0.0.1:${port}`);

  step = 'starting hapticctl view';
  const bridge = startChild('hapticctl view', args.hapticctl,
    ['view', '--server', `127.0.0.1:${port}`, '--scene', sceneName, '--http', '127.0.0.1:0']);
  const url = (await waitForLine(bridge, /viewer on (http:\/\/127\.0\.0\.1:\d+\/\S*)/, 15_000))[1];
  log(`viewer on ${url}`);

  const token = new URL(url).searchParams.get('token');
  check(/^[0-9a-f]{64}$/.test(token ?? ''), `the announced address carries no token: ${url}`);

  step = 'opening two pages';
  const context = await browser.newContext({ viewport: { width: 1000, height: 700 } });
  for (const key of ['a', 'b']) {
    const page = await context.newPage();
    page.on('console', (m) => { if (m.type() === 'error') consoleLines.push(`${key}: ${m.text()}`); });
    page.on('pageerror', (e) => consoleLines.push(`${key}: page error: ${e.message}`));
    pages[key] = page;
    const response = await page.goto(url, { timeout: 10_000 });
    const headers = response.headers();
    check(/default-src 'self'/.test(headers['content-security-policy'] ?? '') &&
          /frame-ancestors 'none'/.test(headers['content-security-policy']) &&
          headers['x-content-type-options'] === 'nosniff',
          `page ${key} came without its security headers: ${JSON.stringify(headers)}`);
  }
  const { a, b } = pages;
  for (const [key, page] of Object.entries(pages)) {
    try {
      await waitUntil(page, () => window.viewerState?.connected && window.viewerState.frames > 0,
                      20_000);
    } catch {
      throw new Failure(`page ${key} is not connected with frames within 20 s: ` +
                        `viewerState = ${brief(await state(page))}`);
    }
  }

  check(!a.url().includes('token='), `page A still shows its token: ${a.url()}`);
  const policyErrors = consoleLines.filter((line) => /Content Security Policy/i.test(line));
  check(policyErrors.length === 0, `the page broke its own policy: ${policyErrors.join(' | ')}`);

  step = 'the edge: origins and the token';
  // Whether a WebSocket to the bridge opens from `page` (true) or is refused.
  const opens = (page, wsUrl) => page.evaluate((u) => new Promise((resolve) => {
    const ws = new WebSocket(u);
    ws.onopen = () => { ws.close(); resolve(true); };
    ws.onclose = () => resolve(false);
  }), wsUrl);
  const wsBase = `ws://${new URL(url).host}/ws`;
  // Another site: a page this test serves from a port of its own.
  const site = http.createServer((request, response) => {
    response.writeHead(200, { 'content-type': 'text/html' });
    response.end('<!doctype html><title>another site</title>');
  });
  await new Promise((resolve) => site.listen(0, '127.0.0.1', resolve));
  try {
    const other = await context.newPage();
    await other.goto(`http://127.0.0.1:${site.address().port}/`, { timeout: 10_000 });
    check(!(await opens(other, `${wsBase}?token=${token}`)),
          'a page of another origin opened the bridge\'s WebSocket with the token');
    await other.close();
  } finally {
    site.close();
  }
  const wrong = token.replace(/^./, (c) => (c === 'a' ? 'b' : 'a'));
  check(!(await opens(b, wsBase)), 'the page\'s own origin opened the WebSocket without the token');
  check(!(await opens(b, `${wsBase}?token=${wrong}`)),
        'the page\'s own origin opened the WebSocket with a wrong token');
  check(await opens(b, `${wsBase}?token=${token}`),
        'the page\'s own origin could not open the WebSocket with the token');
  log('the edge: another origin and a missing or wrong token are refused');

  step = 'page A takes the probe';
  await a.evaluate(() => window.viewerTest.take('probe'));
  try {
    await waitUntil(a, () => window.viewerState.heldTool === 'probe', 15_000);
  } catch {
    throw new Failure(`heldTool is not 'probe' 15 s after take('probe'): ${brief(await state(a))}`);
  }

  step = 'a mouse drag on page A';
  const canvas = await a.locator('canvas').first().boundingBox();
  check(canvas, 'page A has no visible canvas');
  const posesBefore = (await state(a)).posesSent ?? 0;
  const x0 = canvas.x + canvas.width / 2;
  const y0 = canvas.y + canvas.height / 2;
  await a.mouse.move(x0, y0);
  await a.mouse.down();
  await a.mouse.move(x0 + 40, y0 - 20, { steps: 10 });
  await a.mouse.up();
  try {
    await waitUntil(a, (n) => window.viewerState.posesSent > n, 10_000, posesBefore);
  } catch {
    throw new Failure(`posesSent did not grow after a mouse drag (was ${posesBefore}): ` +
                      brief(await state(a)));
  }

  step = 'moving the probe onto the organ';
  // The drag moved the probe by an unknown amount: put it back above its start.
  const dragged = await settledDeviceP(a, 3000);
  check(dragged, `no tools.probe.device_p on page A: ${brief(await state(a))}`);
  const back = probeStart.map((v, i) => v - dragged[i]);
  await a.evaluate((d) => window.viewerTest.moveBy(d), back);
  await settledDeviceP(a, 2000);
  let contact = false;
  for (let i = 0; i < 10 && !contact; i++) {
    await a.evaluate(() => window.viewerTest.moveBy([0, 0, -0.01]));
    contact = await waitUntil(a, () => window.viewerState.contacts?.length > 0, 1500)
      .then(() => true, () => false);
  }
  check(contact, `no contact after lowering the probe 10 cm: ${brief(await state(a))}`);
  // The first contact may be a bare touch (no depth, no force): press 5 mm in.
  await a.evaluate(() => window.viewerTest.moveBy([0, 0, -0.005]));

  step = 'checking page A';
  // Frames keep coming: give the arrows and highlights a moment to catch up.
  await waitUntil(a, () => {
    const s = window.viewerState;
    const sum = (p) => Object.entries(s.highlighted ?? {})
      .filter(([k, v]) => k.startsWith(p) && v > 0).length;
    return s.contacts?.length > 0 && sum('tool_') > 0 && sum('object_') > 0 &&
           s.arrows?.force && s.arrows?.reversing_vector && s.tools?.probe?.force_magnitude_n > 0;
  }, 15_000).catch(() => {});
  const sa = await state(a);
  const problems = [];
  if (!(sa.contacts?.length > 0)) problems.push('no contacts');
  if (!(sumKeys(sa.highlighted, 'object_') > 0)) problems.push('no object-side feature highlighted');
  if (!(sumKeys(sa.highlighted, 'tool_') > 0)) problems.push('no tool-side feature highlighted');
  if (sa.arrows?.reversing_vector !== true) problems.push('no reversing-vector arrow');
  if (sa.arrows?.force !== true) problems.push('no force arrow');
  if (!(probeOf(sa)?.force_magnitude_n > 0)) problems.push('tools.probe.force_magnitude_n is not > 0');
  check(problems.length === 0, `page A: ${problems.join('; ')}: ${brief(sa)}`);
  log(`page A: ${sa.contacts.length} contact(s), highlighted ${JSON.stringify(sa.highlighted)}, ` +
      `force ${probeOf(sa).force_magnitude_n} N`);

  step = 'F frames the probe';
  const wide = (await state(a)).camera;
  await a.keyboard.press('f');
  const near = (await state(a)).camera;
  const probeNow = devicePOf(await state(a));
  const off = Math.hypot(...near.target.map((v, i) => v - probeNow[i]));
  check(near.distance < 0.15 && near.distance < wide.distance / 3 && off < 0.03,
        `F did not frame the probe: camera ${JSON.stringify(wide)} -> ${JSON.stringify(near)}, ` +
        `probe at ${JSON.stringify(probeNow)}`);
  log(`F: camera ${wide.distance.toFixed(3)} m -> ${near.distance.toFixed(3)} m from its target`);

  step = 'checking page B';
  let pa = null, pb = null, sb = null;
  const end = Date.now() + 5000;
  while (Date.now() < end) {
    pa = devicePOf(await state(a));
    sb = await state(b);
    pb = devicePOf(sb);
    if (pa && pb && pa.every((v, i) => Math.abs(v - pb[i]) <= 1e-6)) break;
    await sleep(100);
  }
  check(pa && pb && pa.every((v, i) => Math.abs(v - pb[i]) <= 1e-6),
        `page B's probe device_p ${JSON.stringify(pb)} is not page A's ${JSON.stringify(pa)}`);
  const holder = holderOf(sb);
  check(typeof holder === 'string' ? holder.length > 0 : holder != null && holder !== '',
        `page B shows no holder for the probe: ${brief(sb)}`);
  log(`page B: probe at ${JSON.stringify(pb)}, held by ${JSON.stringify(holder)}`);

  step = 'two pages, two tools';
  // A second tool joins the scene; page B drives it while page A drives the
  // probe, and each page sees both tools where their drivers put them.
  const add = startChild('hapticctl objects add', args.hapticctl,
    ['objects', 'add', '--server', `127.0.0.1:${port}`, 'probe on torus', 'stylus', '--kind', 'tool',
     '--box', '0.01,0.01,0.01', '--pose', '0.05,0,0.15,0,0,0']);
  const addStatus = await new Promise((resolve) => add.proc.on('exit', resolve));
  check(addStatus === 0, `hapticctl objects add exited with ${addStatus}`);
  await waitUntil(b, () => window.viewerState.tools?.stylus, 15_000);
  const taken = await b.evaluate(() => window.viewerTest.take('stylus'));
  // Up to 15 s: on a loaded machine the bridge's device stream takes seconds to start.
  await waitUntil(b, () => window.viewerState.heldTool === 'stylus', 15_000)
    .catch(() => {});
  const sbTake = await state(b);
  const driveText = await b.evaluate(() => document.getElementById('drive-state')?.textContent);
  check(sbTake?.heldTool === 'stylus',
        `page B did not take the stylus: the take answered ${JSON.stringify(taken)}, the page ` +
        `says ${JSON.stringify(driveText)}`);
  await Promise.all([a.evaluate(() => window.viewerTest.moveBy([0, 0, 0.002])),
                     b.evaluate(() => window.viewerTest.moveBy([0.01, 0, 0]))]);
  const toolP = (s, tool) => vec3(s?.tools?.[tool]?.device_p);
  const same = (p, q) => p && q && p.every((v, i) => Math.abs(v - q[i]) <= 1e-6);
  let both = false, sa2 = null, sb2 = null;
  for (const end2 = Date.now() + 15_000; Date.now() < end2 && !both; await sleep(100)) {
    sa2 = await state(a);
    sb2 = await state(b);
    both = same(toolP(sa2, 'stylus'), toolP(sb2, 'stylus')) &&
           same(toolP(sa2, 'probe'), toolP(sb2, 'probe')) &&
           Math.abs(toolP(sb2, 'stylus')[0] - 0.06) <= 1e-6 && sa2.heldTool === 'probe';
  }
  check(both, `the two tools do not agree across the pages: A ${brief(sa2?.tools)}, B ${brief(sb2?.tools)}`);
  log(`two tools: probe at ${JSON.stringify(toolP(sa2, 'probe'))} (A), ` +
      `stylus at ${JSON.stringify(toolP(sb2, 'stylus'))} (B)`);

  step = 'release and take again';
  // R, then T at once: the released stream's end must not cost the new one.
  await a.evaluate(() => window.viewerTest.release());
  await a.evaluate(() => window.viewerTest.take('probe'));
  await waitUntil(a, () => window.viewerState.heldTool === 'probe', 15_000);
  await sleep(500);
  check((await state(a)).heldTool === 'probe', 'page A lost the probe it took again');

  step = 'a device holds a tool';
  // Page B lets the stylus go; hapticctl drive takes it: the pages name it
  // as the frames do (an open server: peer: and the address).
  await b.evaluate(() => window.viewerTest.release());
  const device = startChild('hapticctl drive', args.hapticctl,
    ['drive', '--server', `127.0.0.1:${port}`, '--scene', 'probe on torus', '--tool', 'stylus',
     '--motion', 'sweep', '--amplitude', '0.001', '--duration', '6', '--rate', '100']);
  const deviceEnded = new Promise((resolve) => device.proc.on('exit', resolve));
  // The holder cell of the stylus's row in page B's tools table.
  const stylusHolderCell = () => b.evaluate(() => {
    const row = [...document.querySelectorAll('#tools-body tr')]
      .find((r) => r.cells[0]?.textContent === 'stylus');
    return row?.cells[1]?.textContent ?? null;
  });
  // Up to 15 s (or the drive's end): on a loaded machine the drive takes
  // seconds to start and to take the tool.
  let cellText = null;
  let driveEnded = false;
  deviceEnded.then(() => { driveEnded = true; });
  for (const end3 = Date.now() + 15_000; Date.now() < end3 && !driveEnded; await sleep(100)) {
    cellText = await stylusHolderCell();
    if (/^peer:/.test(cellText ?? '')) break;
  }
  check(/^peer:/.test(cellText ?? ''),
        `page B shows ${JSON.stringify(cellText)} as the stylus's holder, not the device ` +
        `the frames name: ${brief((await state(b)).tools)}`);
  log(`a device holds the stylus: page B shows ${JSON.stringify(cellText)}`);
  check(await deviceEnded === 0, 'hapticctl drive did not end well');

  step = 'bad page messages';
  // From page B, a socket of its own sends what no page sends: each is
  // dropped and counted (the frames' rejected_messages), none moves the probe.
  const before = devicePOf(await state(a));
  const rejected = await b.evaluate((secret) => new Promise((resolve, reject) => {
    const ws = new WebSocket(`ws://${location.host}/ws?token=${secret}`);
    let sent = false;
    ws.onopen = () => {
      for (const bad of ['garbage', '{"type":"pose","tool":"probe","p":[0,0,1e999],"q":[1,0,0,0]}',
                         '{"type":"pose","tool":"probe","p":[0,0,0.5],"q":[1,0,0,0]}',
                         '{"type":"fly","tool":"probe"}']) ws.send(bad);
      sent = true;
    };
    ws.onmessage = (event) => {
      const m = JSON.parse(event.data);
      if (sent && m.type === 'frame' && m.rejected_messages >= 4) {
        ws.close();
        resolve(m.rejected_messages);
      }
    };
    setTimeout(() => reject(new Error('no frame counted the rejected messages')), 5000);
  }), token);
  const after = devicePOf(await state(a));
  check(before && after && before.every((v, i) => Math.abs(v - after[i]) <= 1e-9),
        `a refused message moved the probe: ${JSON.stringify(before)} -> ${JSON.stringify(after)}`);
  log(`bad page messages: ${rejected} rejected, probe unmoved`);

  step = 'hapticctl snapshot';
  // The same page, headless, to a PNG: the probe still pressed into the organ.
  const png = path.join(args.artifacts, 'snapshot.png');
  const shot = startChild('hapticctl snapshot', args.hapticctl,
    ['snapshot', '--server', `127.0.0.1:${port}`, '--scene', 'probe on torus', '--out', png,
     '--width', '800', '--height', '600']);
  const shotStatus = await new Promise((resolve) => shot.proc.on('exit', resolve));
  check(shotStatus === 0, `hapticctl snapshot exited with ${shotStatus}`);
  const magic = fs.readFileSync(png).subarray(0, 8);
  check(magic.equals(Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a])),
        `${png} is not a PNG`);
  log(`snapshot: ${png}, ${fs.statSync(png).size} bytes`);

  step = 'the probe pushes a free body';
  // A 2 cm free cube joins the scene resting on the table, clear of the
  // organ; page A lifts the probe over to it, lowers it 1 cm beside it and
  // pushes it about 9 mm along +x. Page B draws the cube where the frames' bodies
  // put it: pushed along x (its geometry, fetched once, had it at 0.3),
  // still on the table. Motions over the organ happen 13 cm up, above it
  // and below the stylus.
  fs.mkdirSync(args.artifacts, { recursive: true });
  const pebbleFile = path.join(args.artifacts, 'pebble.textproto');
  fs.writeFileSync(pebbleFile, 'name: "pebble" kind: OBJECT_KIND_FREE ' +
    'model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } } ' +
    'pose { position_m { x: 0.3 y: 0.3 z: 0.01 } orientation { w: 1 } }\n');
  const addPebble = startChild('hapticctl objects add (free body)', args.hapticctl,
    ['objects', 'add', '--server', `127.0.0.1:${port}`, 'probe on torus', 'pebble',
     '--from', pebbleFile]);
  const pebbleStatus = await new Promise((resolve) => addPebble.proc.on('exit', resolve));
  check(pebbleStatus === 0, `hapticctl objects add --from ${pebbleFile} exited with ${pebbleStatus}`);
  const pebbleOn = async (page) => vec3((await state(page)).bodies?.pebble?.mesh_p);
  const within = (p, q, tolerance) => p && p.every((v, i) => Math.abs(v - q[i]) <= tolerance);
  let pebble = null;
  // Up to 15 s: on a loaded machine the edit takes seconds to reach page B.
  for (const end4 = Date.now() + 15000; Date.now() < end4; await sleep(100)) {
    pebble = await pebbleOn(b);
    if (within(pebble, [0.3, 0.3, 0.01], 1e-3)) break;
  }
  check(within(pebble, [0.3, 0.3, 0.01], 1e-3),
        `page B does not draw the pebble resting where it was added: ${JSON.stringify(pebble)}`);
  const heldCell = () => b.evaluate(() => [...document.querySelectorAll('#bodies-body tr')]
    .find((r) => r.cells[0]?.textContent === 'pebble')?.cells[2]?.textContent ?? null);
  let held = null;
  for (const end5 = Date.now() + 2000; Date.now() < end5 && held === null; await sleep(100)) {
    held = await heldCell();
  }
  check(held === 'no', `page B's free bodies table shows ${JSON.stringify(held)} as the resting ` +
        'pebble\'s Held');
  const moveProbe = (d) => a.evaluate((offset) => window.viewerTest.moveBy(offset), d);
  const from = await settledDeviceP(a, 2000);
  await moveProbe([0, 0, 0.13 - from[2]]);
  await moveProbe([0.27 - from[0], 0.3 - from[1], 0]);
  await moveProbe([0, 0, 0.011 - 0.13]);
  // To 1 mm short of it, then 9 mm on in 0.1 mm moves: each pose is taken
  // at one step, and a 2 mm move in one step would hit it at 2 m/s.
  await moveProbe([0.009, 0, 0]);
  for (let i = 0; i < 9; i++) await moveProbe([0.001, 0, 0]);
  await settledDeviceP(a, 3000);
  for (const end6 = Date.now() + 5000; Date.now() < end6; await sleep(100)) {
    pebble = await pebbleOn(b);
    if (pebble && pebble[0] > 0.305) break;
  }
  check(pebble && pebble[0] > 0.305 && within(pebble.slice(1), [0.3, 0.01], 2e-3),
        `page B does not draw the pebble pushed along the table: ${JSON.stringify(pebble)}, ` +
        `probe at ${JSON.stringify(devicePOf(await state(a)))}`);
  log(`a free body: the probe pushed the pebble to ${JSON.stringify(pebble)} on page B`);

  step = 'an unknown scene';
  // A bridge for a scene the server lacks: its page says so; the bridge runs on.
  const lost = startChild('hapticctl view (unknown scene)', args.hapticctl,
    ['view', '--server', `127.0.0.1:${port}`, '--scene', 'no such scene', '--http', '127.0.0.1:0']);
  const lostUrl = (await waitForLine(lost, /viewer on (http:\/\/127\.0\.0\.1:\d+\/\S*)/, 15_000))[1];
  const c = await context.newPage();
  await c.goto(lostUrl, { timeout: 10_000 });
  await waitUntil(c, () => /no scene 'no such scene'/.test(document.body.innerText), 15_000)
    .catch(() => {});
  check(/no scene 'no such scene'/.test(await c.evaluate(() => document.body.innerText)),
        `the page of an unknown scene does not say so: ${brief(await state(c))}`);
  // A reload finds the token the page kept (its address no longer has it).
  await c.reload({ timeout: 10_000 });
  await waitUntil(c, () => /no scene 'no such scene'/.test(document.body.innerText), 15_000)
    .catch(() => {});
  check(/no scene 'no such scene'/.test(await c.evaluate(() => document.body.innerText)),
        `after a reload the page of an unknown scene does not say so: ${brief(await state(c))}`);
  check(alive(lost.proc), 'the bridge of an unknown scene ended');

  step = 'the server goes away';
  const termAt = Date.now();
  let exitedAfterMs = null;
  server.proc.once('exit', () => { exitedAfterMs = Date.now() - termAt; });
  server.proc.kill('SIGTERM');
  // Gone once it has exited: while it shuts down, the bridge may still
  // reach it again.
  const exited = await new Promise((resolve) => {
    if (server.proc.exitCode !== null || server.proc.signalCode !== null) resolve(true);
    server.proc.once('exit', () => resolve(true));
    setTimeout(() => resolve(false), 10_000);
  });
  check(exited, `haptic-server did not exit within 10 s of SIGTERM (last lines: ` +
        `${server.log.slice(-3).join(' | ')})`);
  // Polled from here, each reading kept: a wait in the page that ends
  // early (its error swallowed) once left the check to a single reading.
  const readings = [];
  let gone = await state(a);
  for (const until = Date.now() + 10_000; gone?.connected && Date.now() < until;) {
    readings.push(`${Date.now() - termAt} ms: ${gone.status}`);
    await sleep(50);
    gone = await state(a);
  }
  // Which side held on, when it does: the server (still running, or how
  // long it took to exit) or the bridge's view of it.
  check(gone && !gone.connected,
        `page A still shows a connection ${Date.now() - termAt} ms after SIGTERM: ${brief(gone)}; ` +
        `haptic-server ${exitedAfterMs === null ? 'still running' : `exited after ${exitedAfterMs} ms`}` +
        ` (last lines: ${server.log.slice(-3).join(' | ')}); ` +
        `bridge's last lines: ${bridge.log.slice(-3).join(' | ')}; ` +
        `page A's readings: ${readings.slice(0, 3).join(' | ')} ... ${readings.slice(-3).join(' | ')}`);
  check(alive(bridge.proc), 'the bridge ended with the server');
  log(`server gone: page A says "${gone.status}"`);

  step = 'screenshots';
  return finish(0, `PASS (screenshots in ${args.artifacts})`);
}

main().catch((e) => finish(1, e instanceof Failure ? e.message : (e?.stack || String(e))));
