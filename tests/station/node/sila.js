// SPDX-License-Identifier: MIT
// A SiLA 2 client in Node, on @grpc/grpc-js and @grpc/proto-loader (not the project's code): the
// station's protobuf files, calls with the lock identifier as SiLA metadata, observable commands
// followed through their Info, Intermediate and Result calls, SiLA errors decoded.
'use strict';
const fs = require('fs');
const path = require('path');
const grpc = require('@grpc/grpc-js');
const protoLoader = require('@grpc/proto-loader');
const protobuf = require('protobufjs');

const FW = 'sila2.org.silastandard';
const PACKAGES = {
  SiLAService: 'sila2.org.silastandard.core.silaservice.v1',
  LockController: 'sila2.org.silastandard.core.lockcontroller.v1',
  SimulationController: 'sila2.org.silastandard.core.simulationcontroller.v1',
  CancelController: 'sila2.org.silastandard.core.commands.cancelcontroller.v1',
  PauseController: 'sila2.org.silastandard.core.commands.pausecontroller.v1',
  ErrorRecoveryService: 'sila2.org.silastandard.core.errorrecoveryservice.v1',
  ArmController: 'sila2.org.libfbrl.robot.armcontroller.v1',
  RobotController: 'sila2.org.libfbrl.robot.robotcontroller.v1',
  MethodLibrary: 'sila2.org.libfbrl.robot.methodlibrary.v1',
};
const LOCK_KEY = 'sila-org.silastandard-core-lockcontroller-v1-metadata-lockidentifier-bin';

class SilaError extends Error {
  // kind: validationError, definedExecutionError, undefinedExecutionError, frameworkError
  constructor(kind, fields) {
    super(`${kind}: ${fields.errorIdentifier || fields.parameter || fields.errorType || ''}: ${fields.message}`);
    this.kind = kind;
    this.fields = fields;
    this.identifier = kind === 'definedExecutionError' ? fields.errorIdentifier.split('/').pop()
      : kind === 'frameworkError' ? fields.errorType : fields.parameter;
  }
}

class Sila {
  constructor(protoDir) {
    const files = fs.readdirSync(protoDir).filter((f) => f.endsWith('.proto') && f !== 'SiLAFramework.proto');
    this.def = protoLoader.loadSync(files.map((f) => path.join(protoDir, f)),
      { keepCase: true, longs: Number, enums: String, defaults: true, includeDirs: [protoDir] });
    this.root = protobuf.loadSync(files.map((f) => path.join(protoDir, f)).concat(
      [path.join(protoDir, 'SiLAFramework.proto')]));
    this.errorType = this.root.lookupType(`${FW}.SiLAError`);
    this.lockType = this.root.lookupType(`${PACKAGES.LockController}.Metadata_LockIdentifier`);
    this.pkg = grpc.loadPackageDefinition(this.def);
  }

  connect(port, certPem) {
    const creds = certPem ? grpc.credentials.createSsl(certPem) : grpc.credentials.createInsecure();
    // the certificate names localhost too; TLS's server name may not be an address (RFC 6066)
    return new Client(this, `127.0.0.1:${port}`, creds, certPem ? { 'grpc.ssl_target_name_override': 'localhost' } : {});
  }

  decode(err) {
    if (err.code !== grpc.status.ABORTED) return err;
    const e = this.errorType.toObject(this.errorType.decode(Buffer.from(err.details, 'base64')),
      { enums: String, defaults: true });
    const kind = Object.keys(e)[0];
    return new SilaError(kind, e[kind]);
  }
}

class Client {
  constructor(sila, target, creds, options) {
    this.sila = sila;
    this.stubs = {};
    for (const [feature, pkg] of Object.entries(PACKAGES)) {
      const service = pkg.split('.').reduce((o, k) => o[k], sila.pkg)[feature];
      this.stubs[feature] = new service(target, creds, options);
    }
    this.lockId = null;
  }

  close() {
    for (const s of Object.values(this.stubs)) s.close();
  }

  metadata() {
    const md = new grpc.Metadata();
    if (this.lockId !== null) {
      const t = this.sila.lockType;
      md.set(LOCK_KEY, Buffer.from(t.encode(t.create({ LockIdentifier: { value: this.lockId } })).finish()));
    }
    return md;
  }

  // a unary call: the response, or a rejection with the SiLA error
  call(feature, rpc, request = {}) {
    return new Promise((resolve, reject) => {
      this.stubs[feature][rpc](request, this.metadata(), { deadline: Date.now() + 120000 }, (err, res) => {
        if (err) reject(this.sila.decode(err)); else resolve(res);
      });
    });
  }

  get(feature, prop) {
    return this.call(feature, `Get_${prop}`).then((r) => r[prop]);
  }

  // every message of a server stream until it ends, onMessage(message, arrival ms) for each
  stream(feature, rpc, request, onMessage) {
    return new Promise((resolve, reject) => {
      const call = this.stubs[feature][rpc](request, this.metadata());
      call.on('data', (m) => onMessage(m, Date.now(), call));
      call.on('error', (err) => (err.code === grpc.status.CANCELLED ? resolve() : reject(this.sila.decode(err))));
      call.on('end', resolve);
    });
  }

  // start an observable command: its execution UUID
  async start(feature, command, params) {
    const conf = await this.call(feature, command, params);
    return conf.commandExecutionUUID.value;
  }

  // follow an execution to its end: {infos: [[ms, ExecutionInfo]], intermediates, result | error}
  async follow(feature, command, uuid, { intermediate = false, onInfo = null, onIntermediate = null } = {}) {
    const out = { infos: [], intermediates: [] };
    const id = { value: uuid };
    const streams = [this.stream(feature, `${command}_Info`, id, (m, t) => {
      out.infos.push([t, m]);
      if (onInfo) onInfo(m, t);
    })];
    if (intermediate) {
      streams.push(this.stream(feature, `${command}_Intermediate`, id, (m, t) => {
        out.intermediates.push([t, m]);
        if (onIntermediate) onIntermediate(m, t);
      }));
    }
    await Promise.all(streams);
    try {
      out.result = await this.call(feature, `${command}_Result`, id);
    } catch (e) {
      out.error = e;
    }
    return out;
  }
}

module.exports = { Sila, SilaError, PACKAGES, LOCK_KEY };
