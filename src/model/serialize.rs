//! A pointer-free, versioned, checksummed byte form of [`State`] (the FMU's
//! serialized state; loads in another process of the same build).
//!
//! Layout (little-endian): magic `RISERST\0`, format version (u32), the
//! [`Mesh`] counts (nodes, slope nodes, director nodes; u64 each: a cable has
//! no slopes and no directors), then every field in declaration order
//! (f64 / u64; vectors without lengths, which follow from the counts), and an
//! FNV-1a 64 checksum of everything before it.

use super::{HangOff, State};
use crate::math::{M3, V3};
use crate::model::RodConfig;

const MAGIC: &[u8; 8] = b"RISERST\0";
/// 7: the predictor's v̄_{n−2} (`prev2_mean_vel`, `prev2_mean_slope_vel`; issue 28).
const VERSION: u32 = 7;

/// The sizes of a state's vectors: they identify the line model and its mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mesh {
    pub nodes: usize,
    pub slopes: usize,
    pub directors: usize,
}

impl std::fmt::Display for Mesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.directors == 0 {
            write!(f, "a cable of {} nodes", self.nodes)
        } else {
            write!(f, "a rod of {} nodes", self.nodes)
        }
    }
}

/// Why bytes could not be read back as a state.
#[derive(Debug, Clone, PartialEq)]
pub enum StateFormatError {
    TooShort,
    BadMagic,
    UnsupportedVersion(u32),
    BadChecksum,
    /// Node counts differ from the instance's mesh.
    WrongMesh {
        found: Mesh,
        expected: Mesh,
    },
    NonFinite,
}

impl std::fmt::Display for StateFormatError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StateFormatError::TooShort => write!(f, "serialized state is truncated"),
            StateFormatError::BadMagic => write!(f, "not a riser state (bad magic)"),
            StateFormatError::UnsupportedVersion(v) => write!(f, "serialized state format {v} is not supported"),
            StateFormatError::BadChecksum => write!(f, "serialized state is corrupt (checksum mismatch)"),
            StateFormatError::WrongMesh { found, expected } => {
                write!(f, "serialized state is of {found}, this instance has {expected}")
            }
            StateFormatError::NonFinite => write!(f, "serialized state contains non-finite numbers"),
        }
    }
}

/// FNV-1a 64.
pub fn fnv1a(data: &[u8]) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in data {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

struct W<'a>(&'a mut Vec<u8>);

impl W<'_> {
    fn f(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn u(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn v3(&mut self, v: &V3) {
        for c in v.iter() {
            self.f(*c);
        }
    }
    fn m3(&mut self, m: &M3) {
        for c in m.iter() {
            self.f(*c);
        }
    }
}

struct R<'a> {
    b: &'a [u8],
    at: usize,
}

impl R<'_> {
    fn take8(&mut self) -> Result<[u8; 8], StateFormatError> {
        let s = self.b.get(self.at..self.at + 8).ok_or(StateFormatError::TooShort)?;
        self.at += 8;
        Ok(s.try_into().unwrap())
    }
    fn f(&mut self) -> Result<f64, StateFormatError> {
        let v = f64::from_le_bytes(self.take8()?);
        if v.is_finite() { Ok(v) } else { Err(StateFormatError::NonFinite) }
    }
    fn u(&mut self) -> Result<u64, StateFormatError> {
        Ok(u64::from_le_bytes(self.take8()?))
    }
    fn v3(&mut self) -> Result<V3, StateFormatError> {
        Ok(V3::new(self.f()?, self.f()?, self.f()?))
    }
    fn m3(&mut self) -> Result<M3, StateFormatError> {
        let mut m = M3::zeros();
        for c in m.iter_mut() {
            *c = self.f()?;
        }
        Ok(m)
    }
    fn vec3(&mut self, n: usize) -> Result<Vec<V3>, StateFormatError> {
        (0..n).map(|_| self.v3()).collect()
    }
}

impl State {
    /// Appends the byte form of the state (plus `extra` numbers, e.g. the
    /// FMU's inputs) to `out`.
    pub fn write_bytes(&self, extra: &[f64], out: &mut Vec<u8>) {
        let start = out.len();
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&VERSION.to_le_bytes());
        let mut w = W(out);
        let mesh = self.mesh();
        for c in [mesh.nodes, mesh.slopes, mesh.directors] {
            w.u(c as u64);
        }
        w.u(extra.len() as u64);
        for v in extra {
            w.f(*v);
        }
        w.f(self.time);
        for v in self.config.x.iter().chain(&self.config.xp) {
            w.v3(v);
        }
        for d in &self.config.d {
            w.m3(d);
        }
        for v in self.vel.iter().chain(&self.slope_vel) {
            w.v3(v);
        }
        for d in &self.director_vel {
            w.m3(d);
        }
        for v in
            self.mean_vel.iter().chain(&self.mean_slope_vel).chain(&self.prev_mean_vel).chain(&self.prev_mean_slope_vel)
        {
            w.v3(v);
        }
        for v in self.prev2_mean_vel.iter().chain(&self.prev2_mean_slope_vel) {
            w.v3(v);
        }
        w.v3(&self.hang_off.displacement);
        w.v3(&self.hang_off.velocity);
        w.m3(&self.hang_off.rotation);
        w.v3(&self.hang_off.angular_velocity);
        for v in [self.work_top, self.work_hydro, self.dissipated, self.work_anchor, self.algorithmic, self.work_seabed]
        {
            w.f(v);
        }
        for v in &self.hf_accel {
            w.v3(v);
        }
        for v in &self.hf_weight {
            w.f(*v);
        }
        for e in &self.end_accel {
            for v in e {
                w.v3(v);
            }
        }
        for v in &self.mid_reaction {
            w.v3(v);
        }
        w.u(self.steps);
        w.u(self.newton_iterations);
        w.u(self.retries);
        let sum = fnv1a(&out[start..]);
        out.extend_from_slice(&sum.to_le_bytes());
    }

    /// The sizes of the state's vectors.
    pub fn mesh(&self) -> Mesh {
        Mesh { nodes: self.config.x.len(), slopes: self.config.xp.len(), directors: self.config.d.len() }
    }

    /// Reads a state written by [`State::write_bytes`] for the line model and
    /// mesh `expected`; returns it with the extra numbers.
    pub fn read_bytes(bytes: &[u8], expected: Mesh) -> Result<(State, Vec<f64>), StateFormatError> {
        if bytes.len() < 8 + 4 + 8 {
            return Err(StateFormatError::TooShort);
        }
        if &bytes[..8] != MAGIC {
            return Err(StateFormatError::BadMagic);
        }
        let version = u32::from_le_bytes(bytes[8..12].try_into().unwrap());
        if version != VERSION {
            return Err(StateFormatError::UnsupportedVersion(version));
        }
        let (body, sum) = bytes.split_at(bytes.len() - 8);
        if fnv1a(body) != u64::from_le_bytes(sum.try_into().unwrap()) {
            return Err(StateFormatError::BadChecksum);
        }
        let mut r = R { b: body, at: 12 };
        let found = Mesh { nodes: r.u()? as usize, slopes: r.u()? as usize, directors: r.u()? as usize };
        if found != expected {
            return Err(StateFormatError::WrongMesh { found, expected });
        }
        let (n, np, nd) = (found.nodes, found.slopes, found.directors);
        let n_extra = r.u()? as usize;
        if n_extra > 1024 {
            return Err(StateFormatError::TooShort);
        }
        let extra = (0..n_extra).map(|_| r.f()).collect::<Result<Vec<_>, _>>()?;
        let time = r.f()?;
        let x = r.vec3(n)?;
        let xp = r.vec3(np)?;
        let d = (0..nd).map(|_| r.m3()).collect::<Result<Vec<_>, _>>()?;
        let vel = r.vec3(n)?;
        let slope_vel = r.vec3(np)?;
        let director_vel = (0..nd).map(|_| r.m3()).collect::<Result<Vec<_>, _>>()?;
        let mean_vel = r.vec3(n)?;
        let mean_slope_vel = r.vec3(np)?;
        let prev_mean_vel = r.vec3(n)?;
        let prev_mean_slope_vel = r.vec3(np)?;
        let prev2_mean_vel = r.vec3(n)?;
        let prev2_mean_slope_vel = r.vec3(np)?;
        let (displacement, velocity) = (r.v3()?, r.v3()?);
        let hang_off = HangOff { displacement, velocity, rotation: r.m3()?, angular_velocity: r.v3()? };
        let (work_top, work_hydro, dissipated, work_anchor) = (r.f()?, r.f()?, r.f()?, r.f()?);
        let (algorithmic, work_seabed) = (r.f()?, r.f()?);
        let hf_accel = r.vec3(n + np)?;
        let hf_weight = (0..n + np).map(|_| r.f()).collect::<Result<Vec<_>, _>>()?;
        let mut end_accel = [[V3::zeros(); 4]; 2];
        for e in end_accel.iter_mut() {
            for v in e.iter_mut() {
                *v = r.v3()?;
            }
        }
        let mid_reaction = [r.v3()?, r.v3()?];
        let (steps, newton_iterations, retries) = (r.u()?, r.u()?, r.u()?);
        if r.at != body.len() {
            return Err(StateFormatError::TooShort);
        }
        let state = State {
            time,
            config: RodConfig { x, xp, d },
            vel,
            slope_vel,
            director_vel,
            mean_vel,
            mean_slope_vel,
            prev_mean_vel,
            prev_mean_slope_vel,
            prev2_mean_vel,
            prev2_mean_slope_vel,
            hang_off,
            work_top,
            work_hydro,
            dissipated,
            work_anchor,
            algorithmic,
            work_seabed,
            hf_accel,
            hf_weight,
            end_accel,
            mid_reaction,
            steps,
            newton_iterations,
            retries,
        };
        Ok((state, extra))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_is_exact_and_corruption_is_detected() {
        let n = 4;
        let mut s = State::at_rest(
            RodConfig {
                x: (0..n).map(|i| V3::new(i as f64, 0.5, -1.0 / 3.0)).collect(),
                xp: vec![V3::x(); n],
                d: vec![M3::identity(); 2 * n - 1],
            },
            1.25,
        );
        s.vel[1] = V3::new(0.1, 0.2, std::f64::consts::PI);
        s.work_top = 123.456;
        s.steps = 42;
        let mut b = Vec::new();
        s.write_bytes(&[1.0, -2.0], &mut b);
        let m = s.mesh();
        let (t, extra) = State::read_bytes(&b, m).unwrap();
        assert_eq!(t, s);
        assert_eq!(extra, vec![1.0, -2.0]);
        let mut bad = b.clone();
        bad[40] ^= 1;
        assert_eq!(State::read_bytes(&bad, m).unwrap_err(), StateFormatError::BadChecksum);
        assert_eq!(State::read_bytes(&b[..10], m).unwrap_err(), StateFormatError::TooShort);
        assert!(matches!(State::read_bytes(&b, Mesh { nodes: n + 1, ..m }), Err(StateFormatError::WrongMesh { .. })));
        // a cable's state: no slopes, no directors
        let c = State::at_rest(RodConfig { x: s.config.x.clone(), xp: Vec::new(), d: Vec::new() }, 2.0);
        let mut bc = Vec::new();
        c.write_bytes(&[], &mut bc);
        assert_eq!(State::read_bytes(&bc, c.mesh()).unwrap().0, c);
        assert!(matches!(State::read_bytes(&bc, m), Err(StateFormatError::WrongMesh { .. })));
        let mut magic = b.clone();
        magic[0] = b'X';
        assert_eq!(State::read_bytes(&magic, m).unwrap_err(), StateFormatError::BadMagic);
    }
}
