//! `couple_distributed`: the mortar coupling of an interface whose faces are spread over the
//! ranks of a communicator, each rank computing the rows of D and M of the slave nodes it owns.
//!
//! The steps, every one collective:
//! 1. each rank's slave and master boxes and largest face diameters are gathered;
//! 2. each rank sends its slave faces to the ranks whose slave box, grown by two slave face
//!    diameters, they reach: enough for every rank to see every face around its nodes and
//!    around their neighbours;
//! 3. a slave node is owned by the lowest rank holding a face around it; each rank keeps the
//!    received faces around its owned nodes and around those faces' nodes (two layers), so
//!    that its owned rows get every face's contribution and every averaged nodal normal they
//!    use is the whole surface's;
//! 4. each rank's slave faces (its own and those kept), grown by the search's reach, form the
//!    box of master faces it needs; the ranks send their master faces there;
//! 5. each rank couples its faces with the core's [`assemble_coupling`] and keeps the rows it
//!    owns, in the global numbering (node tags). With
//!    [`SearchRadius::Nearest`], if some rank left slave area uncovered, steps 4-5 run again
//!    with the master faces within the search's bound.

use mortar_core::assembly::{assemble_coupling, CouplingOptions, CouplingWarning};
use mortar_core::mesh::SurfaceMesh;
use mortar_core::{Interface, MortarError, SearchRadius, Tolerances};
use mortar_elements::ElementRegistry;
use rustc_hash::{FxHashMap, FxHashSet};
use std::time::Instant;

use crate::error::{DistributedError, Result};
use crate::exchange::{agree, Exchange};
use crate::rows::{RankCounts, RankRows, RankSeconds, TaggedRows};
use crate::wire::{Bounds, Faces, Reader, Writer};

/// What a distributed coupling computes with: the core's options and tolerances, and the
/// element types faces from other ranks may have (the built-in ones by default; register user
/// elements on every rank).
#[derive(Debug, Clone, Default)]
pub struct DistributedOptions {
    /// The coupling's options, as for [`assemble_coupling`].
    pub coupling: CouplingOptions,
    /// The interface's tolerances, as for [`Interface::with_tolerances`]; a
    /// [`SearchRadius::Nearest`] bound is a fraction of the whole slave surface's size, as in
    /// one process.
    pub tolerances: Tolerances,
    /// The element types by name.
    pub elements: ElementRegistry,
}

/// The start of a phase.
struct Lap(Instant);

impl Lap {
    /// Seconds since the last lap (or the start), and a new lap.
    fn lap(&mut self) -> f64 {
        let now = Instant::now();
        let s = (now - self.0).as_secs_f64();
        self.0 = now;
        s
    }
    fn restart(&mut self) {
        self.0 = Instant::now();
    }
}

/// One rank's summary, gathered by all.
struct Summary {
    slave_box: Bounds,
    master_box: Bounds,
    slave_diameter: f64,
    master_diameter: f64,
    slave_faces: u64,
    master_faces: u64,
}

impl Summary {
    fn of(slave: &Faces, master: &Faces) -> Self {
        let mut s = Summary {
            slave_box: Bounds::EMPTY,
            master_box: Bounds::EMPTY,
            slave_diameter: 0.0,
            master_diameter: 0.0,
            slave_faces: slave.len() as u64,
            master_faces: master.len() as u64,
        };
        for f in 0..slave.len() {
            let b = slave.face_box(f);
            s.slave_diameter = s.slave_diameter.max(b.diagonal());
            s.slave_box.union(&b);
        }
        for f in 0..master.len() {
            let b = master.face_box(f);
            s.master_diameter = s.master_diameter.max(b.diagonal());
            s.master_box.union(&b);
        }
        s
    }

    fn write(&self) -> Vec<u8> {
        let mut w = Writer::default();
        self.slave_box.write(&mut w);
        self.master_box.write(&mut w);
        w.f64(self.slave_diameter);
        w.f64(self.master_diameter);
        w.u64(self.slave_faces);
        w.u64(self.master_faces);
        w.bytes
    }

    fn read(bytes: &[u8], rank: usize, from: usize) -> Result<Self> {
        let mut r = Reader::new(bytes, rank, from);
        let s = Summary {
            slave_box: Bounds::read(&mut r)?,
            master_box: Bounds::read(&mut r)?,
            slave_diameter: r.f64()?,
            master_diameter: r.f64()?,
            slave_faces: r.u64()?,
            master_faces: r.u64()?,
        };
        if !r.is_done() {
            return Err(r.malformed("bytes after a summary"));
        }
        Ok(s)
    }
}

/// Sends to each rank the faces of `faces` that `wanted(q, face box)` says it wants and
/// returns what every rank sent here, with the sender of each face; counts the messages and
/// bytes sent to other ranks.
fn send_faces(
    ex: &impl Exchange,
    faces: &Faces,
    wanted: impl Fn(usize, &Bounds) -> bool,
    elements: &ElementRegistry,
    counts: &mut RankCounts,
) -> Result<(Faces, Vec<usize>)> {
    let (rank, size) = (ex.rank(), ex.size());
    let boxes: Vec<Bounds> = (0..faces.len()).map(|f| faces.face_box(f)).collect();
    let (wanted, boxes) = (&wanted, &boxes);
    let which = |q: usize| (0..faces.len()).filter(move |&f| wanted(q, &boxes[f]));
    // This rank's own faces stay here, unencoded.
    let to: Vec<Vec<u8>> = (0..size)
        .map(|q| {
            if q == rank || which(q).next().is_none() {
                Vec::new()
            } else {
                faces.write(which(q))
            }
        })
        .collect();
    for m in to.iter().filter(|m| !m.is_empty()) {
        counts.messages_sent += 1;
        counts.bytes_sent += m.len() as u64;
    }
    let got = ex.all_to_all(&to);
    let read = (|| {
        let mut all = Faces::default();
        let mut from = Vec::new();
        for (q, m) in got.iter().enumerate() {
            let before = all.len();
            if q == rank {
                for f in which(q) {
                    all.push_from(faces, f);
                }
            } else {
                all.read(m, rank, q, elements)?;
            }
            from.extend(std::iter::repeat_n(q, all.len() - before));
        }
        Ok((all, from))
    })();
    agree(ex, read)
}

/// Node coordinates by tag, checked for agreement between ranks.
#[derive(Default)]
struct NodeCoords {
    at: FxHashMap<u64, ([f64; 3], usize)>,
}

impl NodeCoords {
    fn add(
        &mut self,
        faces: &Faces,
        f: usize,
        from: usize,
        rank: usize,
        side: &'static str,
    ) -> Result<()> {
        for (t, x) in faces.nodes(f) {
            match self.at.get(&t) {
                None => {
                    self.at.insert(t, (x, from));
                }
                Some(&(ours, q)) if ours != x => {
                    return Err(DistributedError::InconsistentNode {
                        rank,
                        from: if q == rank { from } else { q },
                        side,
                        tag: t,
                        ours,
                        theirs: x,
                    });
                }
                Some(_) => {}
            }
        }
        Ok(())
    }
}

/// A surface mesh of `faces` (in ascending face tag order, each tag once).
fn mesh_of(faces: &Faces, rank: usize) -> Result<SurfaceMesh> {
    let mut order: Vec<usize> = (0..faces.len()).collect();
    order.sort_by_key(|&f| faces.tags[f]);
    order.dedup_by_key(|f| faces.tags[*f]);
    let mut mesh = SurfaceMesh::with_capacity(faces.node_tags.len(), order.len());
    let mut seen = FxHashSet::default();
    let err = |source| DistributedError::Coupling { rank, source };
    for &f in &order {
        let mut tags = Vec::new();
        for (t, x) in faces.nodes(f) {
            if seen.insert(t) {
                mesh.add_node(t, x).map_err(err)?;
            }
            tags.push(t);
        }
        mesh.add_face_with_tag(faces.tags[f], faces.elements[f], &tags)
            .map_err(err)?;
    }
    Ok(mesh)
}

/// The mortar coupling of the interface whose slave faces are the union of every rank's
/// `slave` and whose master faces that of every rank's `master` (any distribution: the
/// caller's partition; a rank may hold no face of either side). Returns the rows of D and M of
/// the slave nodes this rank owns (the lowest rank holding a face around the node), their
/// columns by node tag. [`gather`](crate::gather) puts every rank's rows together; gathered,
/// they are the one-process coupling's D and M to round-off.
///
/// Collective: every rank of `ex` calls it, with the same options.
///
/// # Errors
/// On every rank when any rank fails (see [`DistributedError`]): a rank's own interface
/// refused or its coupling failed ([`DistributedError::Coupling`]), faces of an element type
/// a rank does not know, a node tag with different coordinates on two ranks;
/// [`DistributedError::NoOverlap`] when no rank has an overlapping pair.
pub fn couple_distributed(
    ex: &impl Exchange,
    slave: &SurfaceMesh,
    master: &SurfaceMesh,
    options: &DistributedOptions,
) -> Result<RankRows> {
    let (rank, size) = (ex.rank(), ex.size());
    let start = Instant::now();
    let mut seconds = RankSeconds::default();
    let mut lap = Lap(Instant::now());
    let own_slave = Faces::of_mesh(slave);
    let own_master = Faces::of_mesh(master);
    let mut counts = RankCounts {
        slave_faces: own_slave.len(),
        master_faces: own_master.len(),
        ..RankCounts::default()
    };

    // 1. Summaries.
    let all = ex.all_gather(&Summary::of(&own_slave, &own_master).write());
    let summaries = agree(
        ex,
        all.iter()
            .enumerate()
            .map(|(q, b)| Summary::read(b, rank, q))
            .collect::<Result<Vec<_>>>(),
    )?;
    let ds = summaries
        .iter()
        .fold(0.0f64, |a, s| a.max(s.slave_diameter));
    let dm = summaries
        .iter()
        .fold(0.0f64, |a, s| a.max(s.master_diameter));
    let mut whole_slave = Bounds::EMPTY;
    for s in &summaries {
        whole_slave.union(&s.slave_box);
    }
    let slave_faces_total: u64 = summaries.iter().map(|s| s.slave_faces).sum();
    seconds.summaries += lap.lap();
    let master_faces_total: u64 = summaries.iter().map(|s| s.master_faces).sum();

    // 2. Slave faces to the ranks whose faces they may neighbour.
    let reach: Vec<Bounds> = summaries
        .iter()
        .map(|s| {
            s.slave_box
                .inflated(2.0 * ds * (1.0 + 1e-9) + f64::EPSILON * ds)
        })
        .collect();
    let (received, from) = send_faces(
        ex,
        &own_slave,
        |q, b| q != rank && b.meets(&reach[q]),
        &options.elements,
        &mut counts,
    )?;
    seconds.slave_exchange += lap.lap();

    // 3. Owners, and the ghost faces kept.
    let kept = agree(ex, ghost_slave_faces(rank, &own_slave, &received, &from))?;
    let (slave_faces, owner) = kept;
    counts.ghost_slave_faces = slave_faces.len() - own_slave.len();

    let mut local_box = Bounds::EMPTY;
    for f in 0..slave_faces.len() {
        local_box.union(&slave_faces.face_box(f));
    }
    let radius = match options.tolerances.search_radius {
        SearchRadius::FaceSize(k) => k * ds,
        SearchRadius::Distance(d) => d,
        SearchRadius::Nearest { .. } => ds,
    };
    let mut reach_of = radius;
    let slave_mesh = agree(ex, mesh_of(&slave_faces, rank))?;
    seconds.ghosts += lap.lap();
    let own_master_tags: FxHashSet<u64> = own_master.tags.iter().copied().collect();
    let mut passes = 0;
    loop {
        passes += 1;
        // 4. Master faces to the ranks whose slave faces they may meet.
        let need = local_box.inflated((reach_of + ds + dm) * (1.0 + 1e-9));
        let mut w = Writer::default();
        need.write(&mut w);
        let needs = ex.all_gather(&w.bytes);
        let needs = agree(
            ex,
            needs
                .iter()
                .enumerate()
                .map(|(q, b)| Bounds::read(&mut Reader::new(b, rank, q)))
                .collect::<Result<Vec<_>>>(),
        )?;
        let (masters, master_from) = send_faces(
            ex,
            &own_master,
            |q, b| b.meets(&needs[q]),
            &options.elements,
            &mut counts,
        )?;
        let masters = agree(ex, checked_masters(rank, masters, &master_from))?;
        seconds.master_exchange += lap.lap();
        let mut ghosts: Vec<u64> = masters
            .tags
            .iter()
            .copied()
            .filter(|t| !own_master_tags.contains(t))
            .collect();
        ghosts.sort_unstable();
        ghosts.dedup();
        counts.ghost_master_faces = ghosts.len();

        // 5. The coupling of this rank's faces, and its owned rows.
        let coupled = agree(
            ex,
            couple_local(
                rank,
                &slave_mesh,
                &masters,
                options,
                (&whole_slave, &local_box),
                &mut seconds,
            ),
        )?;
        lap.restart();
        let uncovered = coupled.as_ref().is_some_and(|c| {
            c.warnings
                .iter()
                .any(|w| matches!(w, CouplingWarning::UncoveredSlaveArea { .. }))
        });
        let any_uncovered = ex
            .all_gather(&[u8::from(uncovered)])
            .iter()
            .any(|b| b.first() == Some(&1));
        if let (SearchRadius::Nearest { bound }, true, 1) =
            (options.tolerances.search_radius, any_uncovered, passes)
        {
            reach_of = reach_of.max(bound * whole_slave.diagonal() + ds);
            continue;
        }
        let pairs = coupled.as_ref().map_or(0, |c| c.stats.pairs as u64);
        let total_pairs: u64 = ex
            .all_gather(&pairs.to_le_bytes())
            .iter()
            .map(|b| u64::from_le_bytes(b[..8].try_into().unwrap_or([0; 8])))
            .sum();
        if total_pairs == 0 {
            return Err(DistributedError::NoOverlap {
                ranks: size,
                slave_faces: slave_faces_total as usize,
                master_faces: master_faces_total as usize,
            });
        }
        counts.pairs = pairs as usize;
        counts.passes = passes;
        let master_nodes: Vec<u64> = {
            let mut t: Vec<u64> = own_master.node_tags.clone();
            t.sort_unstable();
            t.dedup();
            t
        };
        let mut rows = owned_rows(coupled, &owner, rank, master_nodes, counts);
        seconds.rows += lap.lap();
        seconds.total = start.elapsed().as_secs_f64();
        rows.seconds = seconds;
        return Ok(rows);
    }
}

/// The received slave faces this rank keeps (two layers around its owned nodes) after its
/// own, and each local node's owner.
fn ghost_slave_faces(
    rank: usize,
    own: &Faces,
    received: &Faces,
    from: &[usize],
) -> Result<(Faces, FxHashMap<u64, usize>)> {
    let mut coords = NodeCoords::default();
    let mut owner: FxHashMap<u64, usize> = FxHashMap::default();
    for f in 0..own.len() {
        coords.add(own, f, rank, rank, "slave")?;
        for (t, _) in own.nodes(f) {
            owner.insert(t, rank);
        }
    }
    for f in 0..received.len() {
        for (t, _) in received.nodes(f) {
            if let Some(o) = owner.get_mut(&t) {
                *o = (*o).min(from[f]);
            }
        }
    }
    let owned = |t: &u64| owner.get(t) == Some(&rank);
    // Layer one: faces around owned nodes; their nodes, with those of own faces around owned
    // nodes, are where the normals must be whole.
    let mut near: FxHashSet<u64> = FxHashSet::default();
    let mut layer_one = vec![false; received.len()];
    for (f, one) in layer_one.iter_mut().enumerate() {
        if received.nodes(f).any(|(t, _)| owned(&t)) {
            *one = true;
            near.extend(received.nodes(f).map(|(t, _)| t));
        }
    }
    for f in 0..own.len() {
        if own.nodes(f).any(|(t, _)| owned(&t)) {
            near.extend(own.nodes(f).map(|(t, _)| t));
        }
    }
    let own_tags: FxHashSet<u64> = own.tags.iter().copied().collect();
    let mut faces = own.clone();
    let mut taken: FxHashSet<u64> = FxHashSet::default();
    for f in 0..received.len() {
        let keep = layer_one[f] || received.nodes(f).any(|(t, _)| near.contains(&t));
        if keep && !own_tags.contains(&received.tags[f]) && taken.insert(received.tags[f]) {
            coords.add(received, f, from[f], rank, "slave")?;
            faces.push_from(received, f);
        }
    }
    Ok((faces, owner))
}

/// The master faces received, each tag once, their nodes' coordinates checked.
/// ([`mesh_of`] takes each tag once.)
fn checked_masters(rank: usize, faces: Faces, from: &[usize]) -> Result<Faces> {
    let mut coords = NodeCoords::default();
    let mut taken: FxHashSet<u64> = FxHashSet::default();
    for f in 0..faces.len() {
        if taken.insert(faces.tags[f]) {
            coords.add(&faces, f, from[f], rank, "master")?;
        }
    }
    Ok(faces)
}

/// The core's coupling of this rank's slave faces against the master faces received; `None`
/// when there is nothing to couple (no slave or no master face here, or no overlap).
fn couple_local(
    rank: usize,
    slave: &SurfaceMesh,
    masters: &Faces,
    options: &DistributedOptions,
    (whole_slave, local_box): (&Bounds, &Bounds),
    seconds: &mut RankSeconds,
) -> Result<Option<mortar_core::Coupling>> {
    if slave.face_count() == 0 || masters.len() == 0 {
        return Ok(None);
    }
    let t = Instant::now();
    let err = |source| DistributedError::Coupling { rank, source };
    let master = mesh_of(masters, rank)?;
    let mut tolerances = options.tolerances;
    if let SearchRadius::Nearest { bound } = tolerances.search_radius {
        // The bound is a fraction of the slave surface's size: the whole surface's, not this
        // rank's part's.
        let part = local_box.diagonal();
        if part > 0.0 {
            tolerances.search_radius = SearchRadius::Nearest {
                bound: bound * whole_slave.diagonal() / part,
            };
        }
    }
    let interface = Interface::with_tolerances(slave.clone(), master, tolerances).map_err(err)?;
    let t_coupling = Instant::now();
    seconds.interface += (t_coupling - t).as_secs_f64();
    let coupled = assemble_coupling(&interface, &options.coupling);
    seconds.coupling += t_coupling.elapsed().as_secs_f64();
    match coupled {
        Ok(c) => Ok(Some(c)),
        Err(MortarError::NoOverlap { .. }) => Ok(None),
        Err(e) => Err(err(e)),
    }
}

/// The rows of the slave nodes `rank` owns, in ascending tag order.
fn owned_rows(
    coupled: Option<mortar_core::Coupling>,
    owner: &FxHashMap<u64, usize>,
    rank: usize,
    master_nodes: Vec<u64>,
    counts: RankCounts,
) -> RankRows {
    let mut rows: Vec<u64> = owner
        .iter()
        .filter(|(_, &o)| o == rank)
        .map(|(&t, _)| t)
        .collect();
    rows.sort_unstable();
    let mut d = TaggedRows::default();
    let mut m = TaggedRows::default();
    let mut warnings = Vec::new();
    match coupled {
        None => {
            d.indptr = vec![0; rows.len() + 1];
            m.indptr = vec![0; rows.len() + 1];
        }
        Some(c) => {
            let at: FxHashMap<u64, usize> = c
                .slave_nodes
                .iter()
                .enumerate()
                .map(|(i, &t)| (t, i))
                .collect();
            for &t in &rows {
                match at.get(&t) {
                    Some(&i) => {
                        d.push_row(row_of(&c.d, i, &c.slave_nodes));
                        m.push_row(row_of(&c.m, i, &c.master_nodes));
                    }
                    None => {
                        d.push_row(std::iter::empty());
                        m.push_row(std::iter::empty());
                    }
                }
            }
            warnings = c.warnings;
        }
    }
    RankRows {
        rows,
        d,
        m,
        master_nodes,
        counts,
        warnings,
        seconds: RankSeconds::default(),
    }
}

/// Row `i` of `a`, its columns as the tags `tags` of `a`'s columns.
fn row_of<'a>(
    a: &'a mortar_core::linalg::SparseMatrix,
    i: usize,
    tags: &'a [u64],
) -> impl Iterator<Item = (u64, f64)> + 'a {
    let range = a.indptr().outer_inds_sz(i);
    let cols = &a.indices()[range.clone()];
    let vals = &a.data()[range];
    cols.iter().zip(vals).map(move |(&k, &v)| (tags[k], v))
}
