// SPDX-License-Identifier: MIT
// fbrl-station driven by a client the project did not write (Node's @grpc/grpc-js and
// @grpc/proto-loader from the lock file beside this file), as a lab scheduler drives it: it
// lists the features, locks the station (a second client is refused), moves the arm. fbrlsim's
// command log is the truth of what the controller ran. Run by ctest (station_node) with
// FBRL_SIM, FBRL_STATION, FBRL_STATION_PROTO and FBRL_STATION_TESTS set.
'use strict';
const assert = require('node:assert/strict');
const fs = require('fs');
const path = require('path');
const { spawn } = require('child_process');
const { Sila } = require('./sila');

const ROOT = path.resolve(__dirname, '..', '..', '..');
const WORK = process.env.FBRL_STATION_TESTS || fs.mkdtempSync('/tmp/station-node-');
const SITES = path.join(ROOT, 'examples', 'station', 'asps_sites.fbrl');
const START_MS = 60000;

function readLine(stream, re, ms) {
  return new Promise((resolve, reject) => {
    let buf = '';
    const timer = setTimeout(() => reject(new Error(`no line matching ${re} in ${ms} ms:\n${buf}`)), ms);
    const onData = (d) => {
      buf += d;
      const m = buf.match(re);
      if (m) {
        clearTimeout(timer);
        stream.off('data', onData);
        resolve(m);
      }
    };
    stream.setEncoding('utf8');
    stream.on('data', onData);
  });
}

class Process {
  constructor(argv) {
    this.proc = spawn(argv[0], argv.slice(1), { stdio: ['ignore', 'pipe', 'pipe'] });
    this.err = '';
    this.proc.stderr.on('data', (d) => { this.err += d; });
    this.exited = new Promise((resolve) => this.proc.on('exit', resolve));
  }

  stop() {
    if (this.proc.exitCode === null && this.proc.signalCode === null) this.proc.kill('SIGTERM');
    return this.exited;
  }
}

async function startSim(dir, args = []) {
  fs.mkdirSync(dir, { recursive: true });
  const log = path.join(dir, 'sim.log');
  const sim = new Process([process.env.FBRL_SIM, '--status-extra', '--log', log].concat(args));
  const m = await readLine(sim.proc.stdout, /^(\/dev\/\S+)\n/, START_MS);
  sim.port = m[1];
  sim.log = () => (fs.existsSync(log) ? fs.readFileSync(log, 'utf8').split('\n').filter((l) => l) : []);
  return sim;
}

async function startStation(dir, args) {
  const st = new Process([process.env.FBRL_STATION, '--sila', '127.0.0.1:0', '--data', dir, '--no-discovery']
    .concat(args));
  const m = await readLine(st.proc.stderr, /SiLA 2 on [^ ]+:(\d+) /, START_MS);
  st.port = Number(m[1]);
  st.cert = fs.readFileSync(path.join(dir, 'cert.pem'));
  return st;
}

const s = (value) => ({ value });
const place = (name, index = 0) => ({ Place: { PlaceName: s(name) }, Index: s(index) });
const site = (device, index) => ({ Site: { Device: s(device), SiteIndex: s(index) } });

async function expectError(promise, identifier) {
  try {
    await promise;
  } catch (e) {
    assert.equal(e.identifier, identifier, e.message);
    return e;
  }
  assert.fail(`no ${identifier} error`);
}

async function main() {
  fs.rmSync(WORK, { recursive: true, force: true });  // the emulator's log must be this run's alone
  const sila = new Sila(process.env.FBRL_STATION_PROTO);
  const sim = await startSim(path.join(WORK, 'sim'), ['--time-scale', '20']);
  const station = await startStation(path.join(WORK, 'station'), ['--port', sim.port, SITES]);
  const scheduler = sila.connect(station.port, station.cert);
  const other = sila.connect(station.port, station.cert);
  try {
    // the features, and each one's definition
    const features = (await scheduler.get('SiLAService', 'ImplementedFeatures')).map((f) => f.value);
    for (const f of ['org.silastandard/core/SiLAService/v1', 'org.silastandard/core/LockController/v1',
      'org.silastandard/core/SimulationController/v1', 'org.libfbrl/robot/ArmController/v1',
      'org.libfbrl/robot/RobotController/v1']) {
      assert.ok(features.includes(f), `${f} is not implemented: ${features}`);
    }
    for (const f of features) {
      const def = await scheduler.call('SiLAService', 'GetFeatureDefinition', { FeatureIdentifier: s(f) });
      assert.match(def.FeatureDefinition.value, new RegExp(`<Identifier>${f.split('/')[2]}</Identifier>`));
    }
    console.log(`features: ${features.length}`);

    // the lock: the scheduler takes the station; another client is refused
    await scheduler.call('LockController', 'LockServer', { LockIdentifier: s('node-scheduler'), Timeout: s(60) });
    scheduler.lockId = 'node-scheduler';
    assert.equal((await other.get('LockController', 'IsLocked')).value, true);
    await expectError(other.start('ArmController', 'Home', {}), 'INVALID_METADATA');
    other.lockId = 'not-mine';
    await expectError(other.start('ArmController', 'Home', {}), 'InvalidLockIdentifier');
    assert.ok(!sim.log().includes('HOME'), 'a refused client moved the arm');
    console.log('locked: the second client refused twice, nothing sent');

    // observable commands under the lock
    let run = await scheduler.follow('ArmController', 'Home', await scheduler.start('ArmController', 'Home', {}));
    assert.ok(run.result, run.error && run.error.message);
    assert.equal(run.infos[run.infos.length - 1][1].commandStatus, 'finishedSuccessfully');
    assert.ok(sim.log().includes('HOME'));
    run = await scheduler.follow('ArmController', 'MoveToPlace',
      await scheduler.start('ArmController', 'MoveToPlace', place('SEPARATOR')));
    assert.ok(run.result, run.error && run.error.message);
    assert.ok(sim.log().some((l) => /^POINT FBRLT\d,15,5,4,0,-90,0$/.test(l)));
    run = await scheduler.follow('RobotController', 'MovePlate', await scheduler.start('RobotController',
      'MovePlate', { OriginSite: site('HEATING-BLOCK', 0), DestinationSite: site('SEPARATOR', 0), PlateType: s('TUBE') }));
    assert.ok(run.result, run.error && run.error.message);
    run = await scheduler.follow('ArmController', 'MoveToPlace',
      await scheduler.start('ArmController', 'MoveToPlace', place('NOWHERE')));
    assert.equal(run.error.identifier, 'UnknownPlace');
    console.log('Home, MoveToPlace, MovePlate: done; an unknown place refused');

    await scheduler.call('LockController', 'UnlockServer', { LockIdentifier: s('node-scheduler') });
    assert.equal((await other.get('LockController', 'IsLocked')).value, false);
  } finally {
    scheduler.close();
    other.close();
    await station.stop();
    await sim.stop();
  }
  console.log('station_node: all passed');
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
