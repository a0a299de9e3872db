// SPDX-License-Identifier: Apache-2.0
// The status page in a real headless browser (Debian's chromium through
// playwright-core): gnssemud on free ports, the page loaded once, live data
// must arrive without a reload, and the DOM must show the same satellites and
// fix as /api/status for the same epoch. Saves a screenshot as an artifact.
// With --gnssemu, also `gnssemu batch --report` over a static hour (or the
// given config and truth) opened from file://: every chart drawn, no page
// error, the summary's figures those of the run; screenshot report.png.
// Usage: node status_page_browser.mjs --gnssemud PATH --artifacts DIR [--config FILE] [--chromium PATH]
//   [--wait-s S]: watch S seconds more before the screenshot (docs/images: a longer history)
//   [--gnssemu PATH [--report-config FILE --report-truth FILE] [--cn0-reference FILE]]
//   [--sender 'ARGS']: tools/senders/send_truth.py ARGS drives the daemon (docs/images)
//   [--driver-dir DIR]: where playwright-core is installed (npm ci from
//   tests/integration/browser/package-lock.json when it is missing there;
//   default: the build dir's browser-driver, as CMake passes it)
// Exit 77 (skip) only when chromium is missing or cannot start; a driver that
// cannot be installed is a failure.
import { spawn, spawnSync } from 'node:child_process';
import dgram from 'node:dgram';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

const args = Object.fromEntries(
  process.argv.slice(2).reduce((acc, v, i, all) => (v.startsWith('--') ? [...acc, [v.slice(2), all[i + 1]]] : acc), []));
const chromiumPath = args.chromium || '/usr/bin/chromium';
const here = path.dirname(new URL(import.meta.url).pathname);

function skip(why) {
  console.log(`SKIP: ${why}`);
  process.exit(77);
}
function failNow(why) {
  console.error(`FAIL: ${why}`);
  process.exit(1);
}
if (Number(process.versions.node.split('.')[0]) < 20) {
  failNow(`node ${process.versions.node} is too old: playwright-core 1.65 needs node >= 20`);
}
if (!fs.existsSync(chromiumPath)) skip(`${chromiumPath} not found: chromium cannot start (tools/install-deps.sh installs it)`);

/** playwright-core from driverDir, installed there from the lock file on first use. */
function loadDriver(driverDir) {
  const lock = path.join(here, 'browser');
  const require = createRequire(path.join(driverDir, 'package.json'));
  try {
    return require('playwright-core');
  } catch {
    // Not installed yet (a clean build dir).
  }
  fs.mkdirSync(driverDir, { recursive: true });
  for (const f of ['package.json', 'package-lock.json']) fs.copyFileSync(path.join(lock, f), path.join(driverDir, f));
  const t0 = Date.now();
  const npm = spawnSync('npm', ['ci', '--no-audit', '--no-fund', '--loglevel=error'], { cwd: driverDir, encoding: 'utf8' });
  if (npm.error || npm.status !== 0) {
    failNow(`npm ci in ${driverDir} failed (${npm.error ? npm.error.message : `exit ${npm.status}`}): ${npm.stderr || ''}`);
  }
  console.log(`installed playwright-core in ${driverDir} (${((Date.now() - t0) / 1000).toFixed(1)} s)`);
  return require('playwright-core');
}
const { chromium } = loadDriver(path.resolve(args['driver-dir'] || path.join(here, 'browser')));

const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'gnssemu-status-'));
const artifacts = args.artifacts || tmp;
fs.mkdirSync(artifacts, { recursive: true });
let daemon = null;
let sender = null;
let browser = null;
let log = '';
const waitS = Number(args['wait-s'] || 0);
const deadline = Date.now() + 80000 + waitS * 1000;

function fail(msg) {
  throw new Error(msg);
}

async function cleanup() {
  if (sender && sender.exitCode === null) sender.kill('SIGTERM');
  if (browser) await browser.close().catch(() => {});
  if (daemon && daemon.exitCode === null) {
    daemon.kill('SIGTERM');
    await new Promise((r) => { daemon.once('exit', r); setTimeout(r, 5000); });
  }
  fs.rmSync(tmp, { recursive: true, force: true });
}

async function startDaemon() {
  const argv = ['--truth-port', '0', '--status-port', 'free'];
  if (args.config) argv.push('--config', args.config);
  else argv.push('--pty', path.join(tmp, 'gps0'));
  daemon = spawn(args.gnssemud, argv, { stdio: ['ignore', 'pipe', 'pipe'] });
  daemon.stderr.on('data', (d) => { log += d; });
  let out = '';
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`gnssemud printed no status URL:\n${out}\n${log}`)), 20000);
    daemon.stdout.on('data', (d) => {
      out += d;
      const url = /status page (http:\/\/[^\s]+)/.exec(out);
      const truth = /truth input udp ([\d.]+):(\d+)/.exec(out);
      if (url && truth) {
        clearTimeout(timer);
        resolve({ url: url[1], truthPort: Number(truth[2]) });
      }
    });
    daemon.on('exit', (code) => reject(new Error(`gnssemud exited with ${code}:\n${out}\n${log}`)));
  });
}

/** What the page shows, read from the DOM. */
async function domState(page) {
  return page.evaluate(() => ({
    tow: document.body.dataset.tow,
    epoch: Number(document.body.dataset.epoch || 0),
    fixType: document.getElementById('fix-type').dataset.fixType,
    numUsed: document.getElementById('num-used').textContent,
    numTracked: document.getElementById('num-tracked').textContent,
    lat: document.getElementById('lat').textContent,
    lon: document.getElementById('lon').textContent,
    hdop: document.getElementById('hdop').textContent,
    dropped: document.getElementById('truth-dropped').textContent,
    sats: [...document.querySelectorAll('#sat-table tbody tr')].map((tr) => ({ prn: Number(tr.dataset.prn), state: tr.dataset.state })),
    skyPoints: Chart.getChart('sky').data.datasets.filter((d) => !d.gridLine && !d.mask)
      .flatMap((d) => d.data.map((p) => p.prn)).sort((a, b) => a - b),
    cn0Bars: [...Chart.getChart('cn0').data.labels].sort(),
    marker: window.__loadedOnce === true,
    conn: document.getElementById('conn').textContent,
  }));
}

async function main() {
  try {
    // playwright gives each launch a fresh --user-data-dir.
    browser = await chromium.launch({
      executablePath: chromiumPath,
      headless: true,
      args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
             '--disable-component-update', '--disable-sync'],
    });
  } catch (e) {
    await cleanup();
    skip(`${chromiumPath} cannot start: ${e.message.split('\n')[0]}`);
  }
  const { url, truthPort } = await startDaemon();
  console.log(`status page ${url}, truth port ${truthPort}`);
  if (args.sender) {
    const script = path.resolve(here, '..', '..', 'tools', 'senders', 'send_truth.py');
    sender = spawn('python3', [script, '--port', String(truthPort), ...args.sender.split(' ')], { stdio: 'ignore' });
  }
  const context = await browser.newContext({ viewport: { width: 1400, height: 1900 } });
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(url, { waitUntil: 'load' });
  await page.evaluate(() => { window.__loadedOnce = true; });

  // A malformed truth packet: the page must count it as the API does.
  const sock = dgram.createSocket('udp4');
  await new Promise((r) => sock.send('{"version": 1, "lla": ', truthPort, '127.0.0.1', r));
  sock.close();

  // Live data: the shown epoch advances at least three times without a reload.
  await page.waitForFunction(() => document.getElementById('conn').textContent === 'live', null, { timeout: 15000 });
  const first = (await domState(page)).epoch;
  await page.waitForFunction((e0) => Number(document.body.dataset.epoch || 0) >= e0 + 3, first, { timeout: 15000 });
  await page.waitForFunction(() => document.getElementById('fix-type').dataset.fixType === '3', null, { timeout: 15000 });
  await page.waitForFunction(() => document.getElementById('truth-dropped').textContent !== '0', null, { timeout: 15000 });

  // The DOM against /api/status of the same epoch.
  let matched = false;
  for (let attempt = 0; attempt < 20 && !matched && Date.now() < deadline; attempt++) {
    const dom = await domState(page);
    const api = await (await fetch(`${url}api/status?history=0`)).json();
    if (String(api.epoch.tow_s) !== dom.tow) {
      await new Promise((r) => setTimeout(r, 150));
      continue;
    }
    matched = true;
    if (!dom.marker) fail('the page was reloaded');
    if (dom.fixType !== String(api.fix.type)) fail(`fix type: DOM ${dom.fixType}, API ${api.fix.type}`);
    if (dom.numUsed !== String(api.fix.num_used)) fail(`used: DOM ${dom.numUsed}, API ${api.fix.num_used}`);
    if (dom.numTracked !== String(api.fix.num_tracked)) fail(`tracked: DOM ${dom.numTracked}, API ${api.fix.num_tracked}`);
    if (dom.lat !== `${api.fix.lat_deg.toFixed(7)}°`) fail(`lat: DOM ${dom.lat}, API ${api.fix.lat_deg}`);
    if (dom.lon !== `${api.fix.lon_deg.toFixed(7)}°`) fail(`lon: DOM ${dom.lon}, API ${api.fix.lon_deg}`);
    if (dom.hdop !== api.fix.dop.hdop.toFixed(2)) fail(`hdop: DOM ${dom.hdop}, API ${api.fix.dop.hdop}`);
    if (dom.dropped !== String(api.truth.dropped)) fail(`truth drops: DOM ${dom.dropped}, API ${api.truth.dropped}`);
    const apiSats = api.satellites.map((s) => ({ prn: s.prn, state: s.state }));
    if (JSON.stringify(dom.sats) !== JSON.stringify(apiSats)) {
      fail(`satellites: DOM ${JSON.stringify(dom.sats)}, API ${JSON.stringify(apiSats)}`);
    }
    const apiPrns = api.satellites.map((s) => s.prn).sort((a, b) => a - b);
    if (JSON.stringify(dom.skyPoints) !== JSON.stringify(apiPrns)) fail(`sky plot PRNs ${dom.skyPoints} vs ${apiPrns}`);
    const barPrns = api.satellites.filter((s) => s.state !== 'below_mask').map((s) => s.sat).sort();  // bars are labelled G07, R12, ...
    if (JSON.stringify(dom.cn0Bars) !== JSON.stringify(barPrns)) fail(`C/N0 bars ${dom.cn0Bars} vs ${barPrns}`);
    if (api.satellites.length < 4 || api.fix.num_used < 4) fail(`too few satellites for a meaningful check: ${api.satellites.length}`);
    console.log(`epoch tow ${dom.tow}: ${apiSats.length} satellites, fix ${api.fix.type_name} with ${api.fix.num_used} used: DOM = API`);
  }
  if (!matched) fail('the DOM never showed the epoch /api/status returned');
  if (errors.length) fail(`page errors: ${errors.join('; ')}`);
  if (waitS > 0) await new Promise((r) => setTimeout(r, waitS * 1000));
  const shot = path.join(artifacts, 'status_page.png');
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`screenshot ${shot}`);
}

/** gnssemu batch --report, the report in the browser, its screenshot. */
async function checkReport() {
  const source = path.resolve(here, '..', '..');
  let truth = args['report-truth'];
  if (!truth) {
    truth = path.join(tmp, 'static.csv');
    fs.writeFileSync(truth, 'gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,522000,48.8738,2.2950,100.0\n' +
                            '2190,525600,48.8738,2.2950,100.0\n');
  }
  const config = args['report-config'] || path.join(source, 'config', 'default.toml');
  const reference = args['cn0-reference'] || path.join(source, 'tests', 'data', 'receiver-logs', 'ublox-8-excerpt.log');
  const dir = path.join(tmp, 'report');
  const run = spawnSync(args.gnssemu, ['batch', '--config', config, '--truth', truth, '--report', dir,
                                       '--cn0-reference', reference], { encoding: 'utf8' });
  if (run.status !== 0) fail(`gnssemu batch --report exited with ${run.status}: ${run.stderr}`);
  const fixes = /fixes (\d+)/.exec(run.stderr);
  const epochs = /epochs (\d+)/.exec(run.stderr);
  const page = await (await browser.newContext({ viewport: { width: 1400, height: 1000 } })).newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) errors.push(`fetched ${r.url()}`); });
  await page.goto(`file://${path.join(dir, 'report.html')}`, { waitUntil: 'load' });
  const shown = await page.evaluate(() => {
    const charts = [...document.querySelectorAll('canvas')].map((c) => Chart.getChart(c)).filter((c) => c);
    const points = charts.map((c) => c.data.datasets.reduce((n, d) => n + d.data.length, 0));
    const kv = Object.fromEntries([...document.querySelectorAll('#summary tr')]
      .map((tr) => [tr.querySelector('th').textContent, tr.querySelector('td').textContent]));
    return { ids: charts.map((c) => c.canvas.id), points, kv };
  });
  if (errors.length) fail(`report page errors: ${errors.join('; ')}`);
  for (const id of ['sky', 'cn0-el', 'error', 'accuracy', 'cdf', 'scatter', 'sats']) {
    const i = shown.ids.indexOf(id);
    if (i < 0) fail(`report: no chart '${id}' (charts: ${shown.ids})`);
    if (shown.points[i] === 0) fail(`report: chart '${id}' is empty`);
  }
  if (!epochs || shown.kv.epochs !== epochs[1]) fail(`report: epochs ${shown.kv.epochs}, batch printed ${epochs && epochs[1]}`);
  if (!fixes || !shown.kv.fixes.startsWith(`${fixes[1]} `)) fail(`report: fixes ${shown.kv.fixes}, batch printed ${fixes && fixes[1]}`);
  const shot = path.join(artifacts, 'report.png');
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`report: ${shown.ids.length} charts, ${shown.kv.epochs} epochs; screenshot ${shot}`);
}

try {
  await main();
  if (args.gnssemu) await checkReport();
  await cleanup();
  console.log('1 passed, 0 failed');
} catch (e) {
  console.error(`FAIL: ${e.message}`);
  console.error(log.split('\n').slice(-20).join('\n'));
  await cleanup();
  process.exit(1);
}
