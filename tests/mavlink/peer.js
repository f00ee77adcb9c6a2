#!/usr/bin/env node
// The independent MAVLink peer for gpilot's tests: node-mavlink (npm, pinned by package-lock.json) reads the
// bytes gpilot-flight writes, and writes bytes for gpilot's decoder to read. No network: stdin -> stdout.
//   node peer.js decode [KEYHEX]  stdin: one hex string per line (a datagram); stdout: one JSON object per packet
//                         (with signed and, given the MAVLink 2 signing key, signatureValid),
//                         then {"summary": {valid, invalid, unknown}}
//   node peer.js encode   stdin: one JSON object per line {msg, seq, sysid, compid, fields: {camelCaseName: v}}
//                         stdout: the v2 frame as one hex line
//   node peer.js table ID...  stdout: {ID: {name, crcExtra, length}} from node-mavlink's registry
//   node peer.js vehicle PORT [--quiet-at=S --quiet-for=S] [NAME=VALUE ...]
//                         a test vehicle on UDP 127.0.0.1:PORT (the one mode with a socket; run it inside a
//                         network namespace): answers PARAM_REQUEST_READ from the NAME=VALUE list (REAL32; a
//                         name not listed gets no answer), flies the body-frame velocity of the last
//                         SET_POSITION_TARGET_LOCAL_NED, sends HEARTBEAT and LOCAL_POSITION_NED at 20 Hz to
//                         whoever wrote last, and applies its own offboard-loss failsafe as PX4 does: no
//                         setpoint for COM_OF_LOSS_T (or GUID_TIMEOUT) seconds while moving -> hold (velocity 0).
//                         With --quiet-at, from S seconds after listening and for --quiet-for seconds it
//                         neither sends nor reads anything (a lost link), then goes on.
//                         stdout: one JSON event a line: listening, param_request, moving, failsafe, quiet, back.
'use strict';
const readline = require('readline');
const { PassThrough } = require('stream');
const { MavLinkPacketSplitter, MavLinkPacketParser, MavLinkProtocolV2, minimal, common } = require('node-mavlink');

const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY };
const BY_NAME = Object.fromEntries(Object.values(REGISTRY).map((c) => [c.MSG_NAME, c]));
const json = (o) => JSON.stringify(o, (k, v) => (typeof v === 'bigint' ? v.toString() : v));

function lines(onLine, onEnd) {
  const rl = readline.createInterface({ input: process.stdin, terminal: false });
  rl.on('line', (l) => { if (l.trim()) onLine(l.trim()); });
  rl.on('close', onEnd);
}

function decode(key) {
  const input = new PassThrough();
  let crcErrors = 0;
  const splitter = new MavLinkPacketSplitter({}, { onCrcError: () => { crcErrors += 1; } });
  const reader = input.pipe(splitter).pipe(new MavLinkPacketParser());
  reader.on('data', (packet) => {
    const h = packet.header;
    const clazz = REGISTRY[h.msgid];
    const data = clazz ? packet.protocol.data(packet.payload, clazz) : null;
    // Plain field values by their registry names (COMMAND_LONG keeps params as _param1.._param7).
    const fields = {};
    if (clazz) for (const f of clazz.FIELDS) fields[f.name.replace(/^_/, '')] = data[f.name];
    process.stdout.write(json({ msg: clazz ? clazz.MSG_NAME : `UNKNOWN_${h.msgid}`, msgid: h.msgid,
      v: h.magic === 0xfd ? 2 : 1, seq: h.seq, sysid: h.sysid, compid: h.compid,
      payloadLength: h.payloadLength, fields,
      signed: !!packet.signature,
      signatureValid: packet.signature && key ? packet.signature.matches(key) : null }) + '\n');
  });
  reader.on('end', () => {
    process.stdout.write(json({ summary: { valid: splitter.validPackages, invalid: splitter.invalidPackages,
      unknown: splitter.unknownPackagesCount, crcErrors } }) + '\n');
  });
  lines((l) => input.write(Buffer.from(l, 'hex')), () => input.end());
}

function encode() {
  lines((l) => {
    const req = JSON.parse(l);
    const clazz = BY_NAME[req.msg];
    if (!clazz) throw new Error(`unknown message ${req.msg}`);
    const msg = new clazz();
    for (const [k, v] of Object.entries(req.fields || {})) msg[k] = v;
    // req.sign = {key: 64 hex digits, linkId, timestamp: ms since the epoch}: MAVLink 2 signing, node-mavlink's own.
    const flags = req.sign ? MavLinkProtocolV2.IFLAG_SIGNED : 0;
    const protocol = new MavLinkProtocolV2(req.sysid, req.compid, flags);
    let bytes = protocol.serialize(msg, req.seq);
    if (req.sign) bytes = protocol.sign(bytes, req.sign.linkId, Buffer.from(req.sign.key, 'hex'), req.sign.timestamp);
    process.stdout.write(bytes.toString('hex') + '\n');
  }, () => {});
}

function table(ids) {
  const out = {};
  for (const id of ids) {
    const c = REGISTRY[id];
    out[id] = c ? { name: c.MSG_NAME, crcExtra: c.MAGIC_NUMBER, length: c.PAYLOAD_LENGTH } : null;
  }
  process.stdout.write(json(out) + '\n');
}

function vehicle(port, assignments) {
  const dgram = require('dgram');
  const params = {};
  let quietAt = Infinity, quietFor = 0;
  for (const a of assignments) {
    const [k, v] = a.split('=');
    if (k === '--quiet-at') quietAt = Number(v);
    else if (k === '--quiet-for') quietFor = Number(v);
    else params[k] = Number(v);
  }
  let started = 0, quiet = false;
  const isQuiet = () => {  // the link down between quietAt and quietAt + quietFor (s after listening)
    const s = (Date.now() - started) / 1000;
    const now = started > 0 && s >= quietAt && s < quietAt + quietFor;
    if (now !== quiet) out({ event: now ? 'quiet' : 'back' });
    quiet = now;
    return now;
  };
  const lossS = params.COM_OF_LOSS_T ?? params.GUID_TIMEOUT ?? Infinity;
  const out = (o) => process.stdout.write(json({ t: Date.now() / 1000, ...o }) + '\n');
  const proto = new MavLinkProtocolV2(1, 1);
  const sock = dgram.createSocket('udp4');
  const input = new PassThrough();
  const reader = input.pipe(new MavLinkPacketSplitter()).pipe(new MavLinkPacketParser());
  let peer = null, seq = 0, lastSetpoint = 0, velocity = [0, 0, 0], moving = false;
  const position = [0, 0, -1.5];
  const send = (msg) => { if (peer && !isQuiet()) sock.send(proto.serialize(msg, seq++ & 255), peer.port, peer.address); };
  reader.on('data', (packet) => {
    const clazz = REGISTRY[packet.header.msgid];
    if (!clazz) return;
    const m = packet.protocol.data(packet.payload, clazz);
    if (clazz === common.SetPositionTargetLocalNed) {
      lastSetpoint = Date.now();
      velocity = [m.vx, m.vy, m.vz];
      const now = Math.hypot(...velocity) > 0.01;
      if (now && !moving) out({ event: 'moving', velocity });
      moving = now;
    } else if (clazz === common.ParamRequestRead) {
      const name = String(m.paramId).replace(/\0.*$/, '');
      out({ event: 'param_request', name, answered: name in params });
      if (!(name in params)) return;
      const v = new common.ParamValue();
      v.paramId = name;
      v.paramValue = params[name];
      v.paramType = common.MavParamType.REAL32;
      v.paramCount = Object.keys(params).length;
      v.paramIndex = Object.keys(params).indexOf(name);
      send(v);
    }
  });
  sock.on('message', (msg, rinfo) => { if (isQuiet()) return; peer = rinfo; input.write(msg); });
  setInterval(() => {  // the failsafe, checked every 10 ms
    if (moving && Date.now() - lastSetpoint > lossS * 1000) {
      out({ event: 'failsafe', since_setpoint_s: (Date.now() - lastSetpoint) / 1000, loss_s: lossS, velocity });
      velocity = [0, 0, 0];
      moving = false;
    }
  }, 10);
  setInterval(() => {  // 20 Hz: integrate (body = NED here: the vehicle keeps yaw 0) and report
    for (let i = 0; i < 3; ++i) position[i] += velocity[i] * 0.05;
    const hb = new minimal.Heartbeat();
    hb.type = minimal.MavType.QUADROTOR;
    hb.autopilot = minimal.MavAutopilot.PX4;
    hb.baseMode = 128 | 1;  // armed, custom mode
    hb.systemStatus = minimal.MavState.ACTIVE;
    hb.mavlinkVersion = 3;
    send(hb);
    const p = new common.LocalPositionNed();
    [p.x, p.y, p.z] = position;
    [p.vx, p.vy, p.vz] = velocity;
    send(p);
  }, 50);
  sock.bind(port, '127.0.0.1', () => { started = Date.now(); out({ event: 'listening', port, params }); });
}

const mode = process.argv[2];
if (mode === 'decode') decode(process.argv[3] ? Buffer.from(process.argv[3], 'hex') : null);
else if (mode === 'encode') encode();
else if (mode === 'table') table(process.argv.slice(3).map(Number));
else if (mode === 'vehicle') vehicle(Number(process.argv[3]), process.argv.slice(4));
else {
  process.stderr.write('usage: node peer.js decode|encode|table ID...|vehicle PORT [NAME=VALUE...]\n');
  process.exit(2);
}
