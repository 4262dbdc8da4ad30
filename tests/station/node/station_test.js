// SPDX-License-Identifier: MIT
// fbrl-station driven by a client the project did not write (Node's @grpc/grpc-js and
// @grpc/proto-loader from the lock file beside this file), as a lab scheduler drives it: it
// lists the features, locks the station (a second client is refused), moves the arm, runs the
// sample-prep method as an observable command (progress at least once a second, the remaining
// time within 10% of the real duration), cancels a second run mid-way (the arm halted, the
// outputs off), and takes a recoverable error through a continuation option. fbrlsim's command
// log is the truth of what the controller ran. Run by ctest (station_node) with FBRL_SIM,
// FBRL_STATION, FBRL_STATION_PROTO and FBRL_STATION_TESTS set.
'use strict';
const assert = require('node:assert/strict');
const fs = require('fs');
const path = require('path');
const { execFileSync, spawn } = require('child_process');
const { Sila } = require('./sila');

const ROOT = path.resolve(__dirname, '..', '..', '..');
const WORK = process.env.FBRL_STATION_TESTS || fs.mkdtempSync('/tmp/station-node-');
const SITES = path.join(ROOT, 'examples', 'station', 'asps_sites.fbrl');
const START_MS = 60000;
const INFO_GAP_MS = 1000; // the Info stream speaks at least this often
const REMAINING_ERROR = 0.10; // of the run's real duration

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
  const st = new Process([process.env.FBRL_STATION, '--sila', '127.0.0.1:0', '--data', dir, '--no-discovery', '--http', 'off']
    .concat(args));
  const m = await readLine(st.proc.stderr, /SiLA 2 on [^ ]+:(\d+) /, START_MS);
  st.port = Number(m[1]);
  st.cert = fs.readFileSync(path.join(dir, 'cert.pem'));
  return st;
}

const s = (value) => ({ value });
const seconds = (d) => Number(d.seconds) + d.nanos / 1e9;
const uuidOf = (value) => ({ CommandExecutionUUID: { UUID: s(value) } });
const param = (name, value) => ({ Name: s(name), Value: s(value) });

// the method library of the run: sample prep and the vial check (a question it asks)
function library() {
  const lib = path.join(WORK, 'lib');
  fs.mkdirSync(path.join(lib, 'methods'), { recursive: true });
  for (const f of ['asps_cell.fbrl', 'asps_cell_objects.fbrl']) fs.copyFileSync(path.join(ROOT, 'examples', f), path.join(lib, f));
  fs.copyFileSync(path.join(ROOT, 'examples', 'methods', 'sample_prep.fbrl'), path.join(lib, 'methods', 'sample_prep.fbrl'));
  fs.copyFileSync(path.join(ROOT, 'tests', 'station', 'methods', 'vial_check.fbrl'),
    path.join(lib, 'methods', 'vial_check.fbrl'));
  return path.join(lib, 'methods');
}

// outputs on after the log's lines (OUTPUT n on, OUTPUT -n off)
function outputsOn(lines) {
  const on = new Set();
  for (const l of lines) {
    const m = l.match(/^OUTPUT (-?\d+)$/);
    if (m) { const n = Number(m[1]); if (n > 0) on.add(n); else on.delete(-n); }
  }
  return on;
}

async function waitFor(predicate, ms, what) {
  const end = Date.now() + ms;
  while (Date.now() < end) {
    if (await predicate()) return;
    await new Promise((r) => setTimeout(r, 20));
  }
  assert.fail(`timed out waiting for ${what}`);
}
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
  const methods = library();
  const inputs = path.join(ROOT, 'examples', 'tube_present.inputs');
  const control = path.join(WORK, 'control');
  execFileSync('mkfifo', [control]);
  // the emulator at the arm's own speed: the dry run predicts real time
  const sim = await startSim(path.join(WORK, 'sim'), ['--inputs', inputs, '--control', control]);
  const fifo = fs.openSync(control, 'w');
  const setInput = (n, on) => fs.writeSync(fifo, `IN ${n} ${on ? 1 : 0}\n`);
  const station = await startStation(path.join(WORK, 'station'), ['--port', sim.port, '--sim-inputs', inputs,
    '--methods', methods, '-e', '20 CONSTANT TIME-SCALE', SITES]);
  const scheduler = sila.connect(station.port, station.cert);
  const other = sila.connect(station.port, station.cert);
  try {
    // the features, and each one's definition
    const features = (await scheduler.get('SiLAService', 'ImplementedFeatures')).map((f) => f.value);
    for (const f of ['org.silastandard/core/SiLAService/v1', 'org.silastandard/core/LockController/v1',
      'org.silastandard/core.commands/CancelController/v1', 'org.silastandard/core.commands/PauseController/v1',
      'org.silastandard/core/SimulationController/v1', 'org.silastandard/core/ErrorRecoveryService/v1',
      'org.libfbrl/robot/ArmController/v1', 'org.libfbrl/robot/RobotController/v1',
      'org.libfbrl/robot/MethodLibrary/v1']) {
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

    await runSamplePrep(scheduler, sim);
    await cancelMidway(scheduler, other, sim);
    await recover(scheduler, sim, setInput);

    await scheduler.call('LockController', 'UnlockServer', { LockIdentifier: s('node-scheduler') });
    assert.equal((await other.get('LockController', 'IsLocked')).value, false);
  } finally {
    fs.closeSync(fifo);
    scheduler.close();
    other.close();
    await station.stop();
    await sim.stop();
  }
  console.log('station_node: all passed');
}

// the sample-prep method as an observable command, judged by the clock and the emulator's log
async function runSamplePrep(scheduler, sim) {
  const before = sim.log().length;
  const uuid = await scheduler.start('MethodLibrary', 'RunMethod', { Method: s('SAMPLE-PREP'),
    Parameters: [param('#SAMPLES', 2), param('REACTION-MIN', 1)] });
  const run = await scheduler.follow('MethodLibrary', 'RunMethod', uuid, { intermediate: true });
  assert.ok(run.result, run.error && run.error.message);
  assert.equal(run.result.Outcome.value, 'completed');
  assert.deepEqual(run.result.Samples.map((x) => [x.Sample.value, x.Outcome.value]), [[1, 'succeeded'], [2, 'succeeded']]);
  const running = run.infos.filter(([, m]) => m.commandStatus === 'running');
  const end = run.infos[run.infos.length - 1][0];
  assert.equal(run.infos[run.infos.length - 1][1].commandStatus, 'finishedSuccessfully');
  const duration = (end - running[0][0]) / 1000;
  let gap = 0;
  let gapAt = 0;
  let worst = 0;
  for (let i = 0; i < running.length; i++) {
    const [t, m] = running[i];
    const g = (i + 1 < running.length ? running[i + 1][0] : end) - t;
    if (g > gap) { gap = g; gapAt = (t - running[0][0]) / 1000; }
    assert.ok(m.estimatedRemainingTime, 'an Info message without the remaining time');
    worst = Math.max(worst, Math.abs(seconds(m.estimatedRemainingTime) - (end - t) / 1000));
  }
  assert.ok(duration > 20, `the run took ${duration} s: tens of seconds expected`);
  assert.ok(gap <= INFO_GAP_MS, `the Info stream was silent for ${gap} ms, ${gapAt} s into the run`);
  assert.ok(worst <= REMAINING_ERROR * duration,
    `the remaining time was off by ${worst.toFixed(2)} s of a ${duration.toFixed(1)} s run`);
  const steps = run.intermediates.map(([, m]) => `${m.Progress.Event.value} ${m.Progress.StepName.value} ${m.Progress.Sample.value}`);
  for (const want of ['StepEnded Recalibrate 0', 'StepEnded Buffer 2', 'StepEnded Reaction 0', 'StepEnded Separation 1',
    'StepEnded Separation 2', 'StepEnded Rinse 2', 'StepEnded Summary 0']) {
    assert.ok(steps.includes(want), `no "${want}" in ${steps}`);
  }
  const log = sim.log().slice(before);
  assert.ok(log.includes('HOME') && log.filter((l) => l === 'OUTPUT 5').length === 2, 'the separations are not in the log');
  assert.equal(outputsOn(log).size, 0);
  console.log(`sample prep: ${duration.toFixed(1)} s, ${running.length} Info messages, at most ${gap} ms apart, ` +
    `remaining time off by at most ${worst.toFixed(2)} s (${(100 * worst / duration).toFixed(1)}%)`);
}

// a second run cancelled while its separation's vacuum is on: halted, outputs off, ON-ABORT
async function cancelMidway(scheduler, other, sim) {
  const before = sim.log().length;
  const uuid = await scheduler.start('MethodLibrary', 'RunMethod', { Method: s('SAMPLE-PREP'),
    Parameters: [param('#SAMPLES', 2), param('REACTION-MIN', 1)] });
  const following = scheduler.follow('MethodLibrary', 'RunMethod', uuid);
  following.catch(() => {}); // awaited below; a failure before that must not go unhandled
  await waitFor(() => sim.log().slice(before).includes('OUTPUT 5'), 120000, 'the separation vacuum');
  await scheduler.call('CancelController', 'CancelCommand', uuidOf(uuid));
  const run = await following;
  await expectError(other.call('CancelController', 'CancelCommand', uuidOf(uuid)), 'InvalidLockIdentifier');
  assert.equal(run.error && run.error.identifier, 'MethodCancelled', run.error && run.error.message);
  assert.equal(run.infos[run.infos.length - 1][1].commandStatus, 'finishedWithError');
  const log = sim.log().slice(before);
  const vacuum = log.indexOf('OUTPUT 5');
  const halt = log.indexOf('HALT', vacuum);
  assert.ok(halt > vacuum, `no HALT after the vacuum went on: ${log.slice(vacuum)}`);
  assert.ok(log.indexOf('READY', halt) > halt, 'ON-ABORT (READY) did not run');
  // off: by the interrupted pulse itself, or by the safe stop after the HALT
  assert.ok(log.indexOf('OUTPUT -5', vacuum) > vacuum, 'the vacuum was never switched off');
  assert.equal(outputsOn(log).size, 0, 'an output is still on');
  assert.ok(!log.slice(halt).includes('OUTPUT 5'), 'the run went on after the cancel');
  console.log(`cancelled mid-way: ${log.slice(halt).join(' ')}`);
}

// a recoverable error: the vial is not on its sensor; put there, the client says Retry
async function recover(scheduler, sim, setInput) {
  setInput(4, false);
  const uuid = await scheduler.start('MethodLibrary', 'RunMethod', { Method: s('VIAL-CHECK'), Parameters: [param('#VIALS', 1)] });
  const following = scheduler.follow('MethodLibrary', 'RunMethod', uuid, { intermediate: true });
  following.catch(() => {});
  let error = null;
  await scheduler.stream('ErrorRecoveryService', 'Subscribe_RecoverableErrors', {}, (m, t, call) => {
    if (m.RecoverableErrors.length) {
      error = m.RecoverableErrors[0].RecoverableError;
      call.cancel();
    }
  });
  assert.equal(error.CommandExecutionUUID.value, uuid);
  assert.deepEqual(error.ContinuationOptions.map((o) => o.ContinuationOption.Identifier.value), ['Retry', 'SkipSample', 'Abort']);
  const reads = sim.log().filter((l) => l === 'TYPEI SIG(4)').length;
  setInput(4, true);
  await scheduler.call('ErrorRecoveryService', 'ExecuteContinuationOption',
    { CommandExecutionUUID: s(uuid), ContinuationOption: s('Retry'), InputData: s('') });
  const run = await following;
  assert.ok(run.result, run.error && run.error.message);
  assert.equal(run.result.Outcome.value, 'completed');
  assert.ok(sim.log().filter((l) => l === 'TYPEI SIG(4)').length > reads, 'the step did not run again');
  const events = run.intermediates.map(([, m]) => m.Progress.Event.value);
  assert.ok(events.includes('WaitingForRecovery') && events.includes('Recovered'), events.join(' '));
  console.log(`recoverable error: "${error.ErrorMessage.value}", Retry chosen, the run completed`);
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
