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

use mortar_core::assembly::{assemble_coupling, CouplingOptions, CouplingWarning, WholeInterface};
use mortar_core::element::ElementRef;
use mortar_core::mesh::SurfaceMesh;
use mortar_core::{Interface, MortarError, SearchRadius, SpatialDim, Tolerances};
use mortar_elements::ElementRegistry;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use crate::error::{DistributedError, Result};
use crate::exchange::{agree, Exchange};
use crate::rows::{RankCounts, RankRows, RankSeconds, TaggedRows};
use crate::wire::{Bounds, FaceSource, Faces, Reader, Writer};

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

/// The box of the slave faces another rank sends to a rank whose slave faces span `slave_box`:
/// two slave face diameters `ds` around it, where the faces around its nodes and around
/// those faces' nodes lie.
pub(crate) fn slave_reach(slave_box: &Bounds, ds: f64) -> Bounds {
    slave_box.inflated(2.0 * ds * (1.0 + 1e-9))
}

/// How far from a slave face the first search looks, for the largest slave face diameter
/// `ds`.
pub(crate) fn search_reach(tolerances: &Tolerances, ds: f64) -> f64 {
    match tolerances.search_radius {
        SearchRadius::FaceSize(k) => k * ds,
        SearchRadius::Distance(d) => d,
        SearchRadius::Nearest { .. } => ds,
    }
}

/// The box of the master faces a rank needs whose slave faces (ghosts included) span
/// `local_box`: the search's reach beyond it, a slave face diameter for the projection's
/// slant and a master face diameter, so that every master face a slave face's search box
/// meets has a node inside.
pub(crate) fn master_need(local_box: &Bounds, reach: f64, ds: f64, dm: f64) -> Bounds {
    local_box.inflated((reach + ds + dm) * (1.0 + 1e-9))
}

/// One rank's summary, gathered by all.
struct Summary {
    slave_box: Bounds,
    master_box: Bounds,
    slave_diameter: f64,
    master_diameter: f64,
    slave_faces: u64,
    master_faces: u64,
    /// The box of the first nodes of the slave faces (the order of the whole's faces).
    anchors: Bounds,
    /// The element types of the slave and master faces, by name.
    slave_types: Vec<String>,
    master_types: Vec<String>,
}

impl Summary {
    fn of(slave: &SurfaceMesh, master: &SurfaceMesh) -> Self {
        let mut s = Summary {
            slave_box: Bounds::EMPTY,
            master_box: Bounds::EMPTY,
            slave_diameter: 0.0,
            master_diameter: 0.0,
            slave_faces: slave.face_count() as u64,
            master_faces: master.face_count() as u64,
            anchors: WholeInterface::anchor_box(slave)
                .map_or(Bounds::EMPTY, |(lo, hi)| Bounds { lo, hi }),
            slave_types: names(slave),
            master_types: names(master),
        };
        for f in 0..slave.face_count() {
            let b = slave.face_box(f);
            s.slave_diameter = s.slave_diameter.max(b.diagonal());
            s.slave_box.union(&b);
        }
        for f in 0..master.face_count() {
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
        self.anchors.write(&mut w);
        for types in [&self.slave_types, &self.master_types] {
            w.u32(types.len() as u32);
            for t in types {
                w.str(t);
            }
        }
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
            anchors: Bounds::read(&mut r)?,
            slave_types: read_names(&mut r)?,
            master_types: read_names(&mut r)?,
        };
        if !r.is_done() {
            return Err(r.malformed("bytes after a summary"));
        }
        Ok(s)
    }
}

/// The names of the element types of `mesh`'s faces.
fn names(mesh: &SurfaceMesh) -> Vec<String> {
    mesh.element_types()
        .iter()
        .map(|e| e.name().to_string())
        .collect()
}

/// A list of names as [`Summary::write`] writes it.
fn read_names(r: &mut Reader<'_>) -> Result<Vec<String>> {
    let n = r.u32()?;
    (0..n).map(|_| r.str()).collect()
}

/// The element types named in `lists` (the ranks', in rank order), each once, in the order
/// first named.
fn resolve<'a>(
    lists: impl Iterator<Item = &'a Vec<String>>,
    elements: &ElementRegistry,
    rank: usize,
) -> Result<Vec<ElementRef>> {
    let mut seen = FxHashSet::default();
    let mut out = Vec::new();
    for (q, list) in lists.enumerate() {
        for name in list {
            if seen.insert(name.as_str()) {
                let e = elements
                    .by_name(name)
                    .ok_or_else(|| DistributedError::UnknownElement {
                        rank,
                        from: q,
                        name: name.clone(),
                    })?;
                out.push(e);
            }
        }
    }
    Ok(out)
}

/// What every rank's coupling must know of the whole interface, from the ranks' summaries and
/// their slave faces' buckets (gathered here: collective).
fn whole_interface(
    ex: &(impl Exchange + ?Sized),
    slave: &SurfaceMesh,
    summaries: &[Summary],
    elements: &ElementRegistry,
) -> Result<Option<WholeInterface>> {
    let rank = ex.rank();
    let mut anchors = Bounds::EMPTY;
    for s in summaries {
        anchors.union(&s.anchors);
    }
    let types = (|| {
        let slave = resolve(summaries.iter().map(|s| &s.slave_types), elements, rank)?;
        let master = resolve(summaries.iter().map(|s| &s.master_types), elements, rank)?;
        Ok((slave, master))
    })();
    let (slave_types, master_types) = agree(ex, types)?;
    let faces: u64 = summaries.iter().map(|s| s.slave_faces).sum();
    let Some(first) = slave_types.first() else {
        return Ok(None);
    };
    let dim = if first.domain().dim() == 1 {
        SpatialDim::Two
    } else {
        SpatialDim::Three
    };
    let anchors = (anchors.lo, anchors.hi);
    // Every rank's buckets, summed bucket by bucket.
    let mine = WholeInterface::bucket_counts(slave, &anchors, faces, dim);
    let mut w = Writer::default();
    for &(b, n) in &mine {
        w.u64(b);
        w.u64(n);
    }
    let mut counts: BTreeMap<u64, u64> = BTreeMap::new();
    for (q, bytes) in ex.all_gather(&w.bytes).iter().enumerate() {
        let mut r = Reader::new(bytes, rank, q);
        while !r.is_done() {
            let (b, n) = (r.u64()?, r.u64()?);
            *counts.entry(b).or_insert(0) += n;
        }
    }
    let counts: Vec<(u64, u64)> = counts.into_iter().collect();
    Ok(Some(WholeInterface::new(
        anchors,
        faces,
        dim,
        &counts,
        slave_types,
        master_types,
        true,
    )))
}

/// Sends to each other rank `q` the faces of `mesh` whose box `wanted(q, box)` accepts, and
/// returns what the other ranks sent here, with each face's sender; counts the messages and
/// bytes sent.
fn send_faces(
    ex: &(impl Exchange + ?Sized),
    mesh: &SurfaceMesh,
    wanted: impl Fn(usize, &Bounds) -> bool,
    elements: &ElementRegistry,
    counts: &mut RankCounts,
) -> Result<(Faces, Vec<usize>)> {
    let (rank, size) = (ex.rank(), ex.size());
    let boxes: Vec<Bounds> = (0..mesh.face_count()).map(|f| mesh.face_box(f)).collect();
    let (wanted, boxes) = (&wanted, &boxes);
    let which = |q: usize| (0..mesh.face_count()).filter(move |&f| wanted(q, &boxes[f]));
    let to: Vec<Vec<u8>> = (0..size)
        .map(|q| {
            if q == rank || which(q).next().is_none() {
                Vec::new()
            } else {
                mesh.write(which(q))
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
            if q != rank {
                let before = all.len();
                all.read(m, rank, q, elements)?;
                from.extend(std::iter::repeat_n(q, all.len() - before));
            }
        }
        Ok((all, from))
    })();
    agree(ex, read)
}

/// The coordinates of the nodes received, by tag, checked against this rank's own nodes and
/// between the senders.
struct NodeCheck<'a> {
    own: &'a SurfaceMesh,
    side: &'static str,
    rank: usize,
    received: FxHashMap<u64, ([f64; 3], usize)>,
}

impl<'a> NodeCheck<'a> {
    fn new(own: &'a SurfaceMesh, side: &'static str, rank: usize) -> Self {
        Self {
            own,
            side,
            rank,
            received: FxHashMap::default(),
        }
    }

    /// Checks the nodes of face `f` of `faces`, which rank `from` sent.
    fn check(&mut self, faces: &Faces, f: usize, from: usize) -> Result<()> {
        for (t, x) in faces.nodes(f) {
            let (ours, q) = match self.own.node_index(t) {
                Some(i) => {
                    let c = self.own.coords()[i as usize];
                    ([c.x, c.y, c.z], self.rank)
                }
                None => *self.received.entry(t).or_insert((x, from)),
            };
            if ours != x {
                return Err(DistributedError::InconsistentNode {
                    rank: self.rank,
                    from: if q == self.rank { from } else { q },
                    side: self.side,
                    tag: t,
                    ours,
                    theirs: x,
                });
            }
        }
        Ok(())
    }
}

/// `own` with the faces of `extra` that `keep` selects appended (those whose tag `own` or an
/// earlier one has skipped), their new nodes added.
fn extended(
    own: &SurfaceMesh,
    extra: &Faces,
    keep: impl Fn(usize) -> bool,
    rank: usize,
) -> Result<SurfaceMesh> {
    let mut mesh = own.clone();
    if extra.len() == 0 {
        return Ok(mesh);
    }
    let err = |source| DistributedError::Coupling { rank, source };
    let mut tags: FxHashSet<u64> = (0..own.face_count()).map(|f| own.face(f).tag).collect();
    let mut node_tags = Vec::new();
    for f in (0..extra.len()).filter(|&f| keep(f)) {
        if !tags.insert(extra.tags[f]) {
            continue;
        }
        node_tags.clear();
        for (t, x) in extra.nodes(f) {
            if mesh.node_index(t).is_none() {
                mesh.add_node(t, x).map_err(err)?;
            }
            node_tags.push(t);
        }
        mesh.add_face_with_tag(extra.tags[f], extra.elements[f], &node_tags)
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
    ex: &(impl Exchange + ?Sized),
    slave: &SurfaceMesh,
    master: &SurfaceMesh,
    options: &DistributedOptions,
) -> Result<RankRows> {
    let (rank, size) = (ex.rank(), ex.size());
    let start = Instant::now();
    let mut seconds = RankSeconds::default();
    let mut lap = Lap(Instant::now());
    let mut counts = RankCounts {
        slave_faces: slave.face_count(),
        master_faces: master.face_count(),
        ..RankCounts::default()
    };

    // 1. Summaries.
    let all = ex.all_gather(&Summary::of(slave, master).write());
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
    let master_faces_total: u64 = summaries.iter().map(|s| s.master_faces).sum();
    seconds.summaries += lap.lap();

    // 2. Slave faces to the ranks whose faces they may neighbour.
    let reach: Vec<Bounds> = summaries
        .iter()
        .map(|s| slave_reach(&s.slave_box, ds))
        .collect();
    let (received, from) = send_faces(
        ex,
        slave,
        |q, b| b.meets(&reach[q]),
        &options.elements,
        &mut counts,
    )?;
    seconds.slave_exchange += lap.lap();

    // What the ranks' couplings must know of the whole interface to sum as it does.
    let mut whole = whole_interface(ex, slave, &summaries, &options.elements)?.map(Arc::new);

    // 3. Owners, and the ghost faces kept.
    let (slave_mesh, owner) = agree(ex, with_ghost_faces(rank, slave, &received, &from))?;
    // Moved into the first pass's interface; built again for a second pass.
    let mut slave_mesh = Some(slave_mesh);
    let local_faces = slave_mesh.as_ref().map_or(0, SurfaceMesh::face_count);
    counts.ghost_slave_faces = local_faces - slave.face_count();
    let mut local_box = Bounds::EMPTY;
    if let Some(mesh) = &slave_mesh {
        for f in 0..mesh.face_count() {
            local_box.union(&mesh.face_box(f));
        }
    }
    seconds.ghosts += lap.lap();
    let mut reach_of = search_reach(&options.tolerances, ds);
    let mut passes = 0;
    loop {
        passes += 1;
        // 4. Master faces to the ranks whose slave faces they may meet.
        let need = master_need(&local_box, reach_of, ds, dm);
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
            master,
            |q, b| b.meets(&needs[q]),
            &options.elements,
            &mut counts,
        )?;
        let checked = (|| {
            let mut check = NodeCheck::new(master, "master", rank);
            for f in 0..masters.len() {
                check.check(&masters, f, master_from[f])?;
            }
            extended(master, &masters, |_| true, rank)
        })();
        let master_mesh = agree(ex, checked)?;
        counts.ghost_master_faces = master_mesh.face_count() - master.face_count();
        seconds.master_exchange += lap.lap();

        // 5. The coupling of this rank's faces, and its owned rows.
        let local = match slave_mesh.take() {
            Some(mesh) => Ok(mesh),
            None => with_ghost_faces(rank, slave, &received, &from).map(|(mesh, _)| mesh),
        };
        let interface = agree(
            ex,
            local.and_then(|local| {
                local_interface(
                    rank,
                    local,
                    master_mesh,
                    options,
                    (&whole_slave, &local_box),
                    &mut seconds,
                )
            }),
        )?;
        if let Some(w) = whole.as_mut() {
            // Both sides of the whole are chains of lines when every rank's are (each rank
            // holds every face around its nodes).
            let chains = interface
                .as_ref()
                .is_none_or(WholeInterface::lines_are_chains);
            let all = ex.all_gather(&[u8::from(chains)]);
            Arc::make_mut(w).set_chains(all.iter().all(|b| b.first() == Some(&1)));
        }
        let coupled = agree(
            ex,
            couple_part(
                rank,
                interface.as_ref(),
                options,
                whole.as_ref(),
                &mut seconds,
            ),
        )?;
        drop(interface);
        lap.restart();
        // Slave faces here and nothing coupled (no master face within reach, or none that
        // overlaps) is uncovered area too, as the core's `NoOverlap` is to one process.
        let uncovered = match &coupled {
            Some(c) => c
                .warnings
                .iter()
                .any(|w| matches!(w, CouplingWarning::UncoveredSlaveArea { .. })),
            None => local_faces > 0,
        };
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
        let mut rows = owned_rows(coupled, slave, &owner, rank, master, counts);
        seconds.rows += lap.lap();
        seconds.total = start.elapsed().as_secs_f64();
        rows.seconds = seconds;
        return Ok(rows);
    }
}

/// This rank's slave faces with the received ones it keeps (two layers around its owned
/// nodes) appended, and the owner of each of its own nodes (by node index of `own`).
pub(crate) fn with_ghost_faces(
    rank: usize,
    own: &SurfaceMesh,
    received: &Faces,
    from: &[usize],
) -> Result<(SurfaceMesh, Vec<usize>)> {
    let mut check = NodeCheck::new(own, "slave", rank);
    let mut owner = vec![rank; own.node_count()];
    for f in 0..received.len() {
        check.check(received, f, from[f])?;
        for (t, _) in received.nodes(f) {
            if let Some(i) = own.node_index(t) {
                owner[i as usize] = owner[i as usize].min(from[f]);
            }
        }
    }
    let own_index = |t: u64| own.node_index(t).map(|i| i as usize);
    let owned = |t: u64| own_index(t).is_some_and(|i| owner[i] == rank);
    // Layer one: received faces around owned nodes. The nodes of the faces around owned
    // nodes (own or received) are where the normals must be whole: own ones marked by index,
    // the others by tag.
    let mut near_own = vec![false; own.node_count()];
    for f in 0..own.face_count() {
        let nodes = own.face(f).nodes;
        if nodes.iter().any(|&n| owner[n as usize] == rank) {
            for &n in nodes {
                near_own[n as usize] = true;
            }
        }
    }
    let mut near_ghost: FxHashSet<u64> = FxHashSet::default();
    let mut layer_one = vec![false; received.len()];
    for (f, one) in layer_one.iter_mut().enumerate() {
        if received.nodes(f).any(|(t, _)| owned(t)) {
            *one = true;
            for (t, _) in received.nodes(f) {
                match own_index(t) {
                    Some(i) => near_own[i] = true,
                    None => {
                        near_ghost.insert(t);
                    }
                }
            }
        }
    }
    let near = |t: u64| match own_index(t) {
        Some(i) => near_own[i],
        None => near_ghost.contains(&t),
    };
    let keep = |f: usize| layer_one[f] || received.nodes(f).any(|(t, _)| near(t));
    let mesh = extended(own, received, keep, rank)?;
    Ok((mesh, owner))
}

/// `mesh`'s faces in ascending tag order: the whole interface's order of them (when its
/// faces ascend by tag, as Gmsh and the generators write them), which the coupling's sums
/// follow (the nodal normals, the ties of the Morton order, the candidates).
fn by_tag(mesh: SurfaceMesh, rank: usize) -> Result<SurfaceMesh> {
    let tags: Vec<u64> = (0..mesh.face_count()).map(|f| mesh.face(f).tag).collect();
    if tags.is_sorted() {
        return Ok(mesh);
    }
    let mut order: Vec<usize> = (0..tags.len()).collect();
    order.sort_unstable_by_key(|&f| tags[f]);
    mesh.part(order)
        .map_err(|source| DistributedError::Coupling { rank, source })
}

/// This rank's interface: its slave faces (its own and the kept ones) against its master
/// faces, each side by tag; `None` when there is nothing to couple (no slave or no master
/// face here).
fn local_interface(
    rank: usize,
    slave: SurfaceMesh,
    master: SurfaceMesh,
    options: &DistributedOptions,
    (whole_slave, local_box): (&Bounds, &Bounds),
    seconds: &mut RankSeconds,
) -> Result<Option<Interface>> {
    if slave.face_count() == 0 || master.face_count() == 0 {
        return Ok(None);
    }
    let t = Instant::now();
    let err = |source| DistributedError::Coupling { rank, source };
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
    let (slave, master) = (by_tag(slave, rank)?, by_tag(master, rank)?);
    let interface = Interface::with_tolerances(slave, master, tolerances).map_err(err)?;
    seconds.interface += t.elapsed().as_secs_f64();
    Ok(Some(interface))
}

/// The core's coupling of this rank's interface as a part of `whole`; `None` when there is
/// nothing to couple (no interface here, or no overlap).
fn couple_part(
    rank: usize,
    interface: Option<&Interface>,
    options: &DistributedOptions,
    whole: Option<&Arc<WholeInterface>>,
    seconds: &mut RankSeconds,
) -> Result<Option<mortar_core::Coupling>> {
    let Some(interface) = interface else {
        return Ok(None);
    };
    let t_coupling = Instant::now();
    let mut coupling = options.coupling.clone();
    coupling.whole = whole.cloned();
    let coupled = assemble_coupling(interface, &coupling);
    seconds.coupling += t_coupling.elapsed().as_secs_f64();
    match coupled {
        Ok(c) => Ok(Some(c)),
        Err(MortarError::NoOverlap { .. }) => Ok(None),
        Err(e) => Err(DistributedError::Coupling { rank, source: e }),
    }
}

/// The rows of the slave nodes `rank` owns (of `own`'s nodes used by a face, `owner[i] ==
/// rank`), in ascending tag order; the master node tags of `master`'s faces.
fn owned_rows(
    coupled: Option<mortar_core::Coupling>,
    own: &SurfaceMesh,
    owner: &[usize],
    rank: usize,
    master: &SurfaceMesh,
    counts: RankCounts,
) -> RankRows {
    let mut used = vec![false; own.node_count()];
    for f in 0..own.face_count() {
        for &n in own.face(f).nodes {
            used[n as usize] = true;
        }
    }
    let mut rows: Vec<u64> = (0..own.node_count())
        .filter(|&i| used[i] && owner[i] == rank)
        .map(|i| own.node_tags()[i])
        .collect();
    rows.sort_unstable();
    let mut d = TaggedRows::default();
    let mut m = TaggedRows::default();
    let mut warnings = Vec::new();
    let mut uncoupled_faces = Vec::new();
    match coupled {
        None => {
            uncoupled_faces = (0..own.face_count()).map(|f| own.face(f).tag).collect();
            d.indptr = vec![0; rows.len() + 1];
            m.indptr = vec![0; rows.len() + 1];
        }
        Some(c) => {
            for (rows_of, a) in [(&mut d, &c.d), (&mut m, &c.m)] {
                rows_of.cols.reserve(a.nnz());
                rows_of.values.reserve(a.nnz());
                rows_of.indptr.reserve(rows.len() + 1);
            }
            // The coupling's rows are its slave nodes in ascending tag order, a superset of
            // `rows`: one merge.
            let mut i = 0;
            for &t in &rows {
                while i < c.slave_nodes.len() && c.slave_nodes[i] < t {
                    i += 1;
                }
                if c.slave_nodes.get(i) == Some(&t) {
                    d.push_row(row_of(&c.d, i, &c.slave_nodes));
                    m.push_row(row_of(&c.m, i, &c.master_nodes));
                } else {
                    d.push_row(std::iter::empty());
                    m.push_row(std::iter::empty());
                }
            }
            warnings = c.warnings;
        }
    }
    let mut master_nodes: Vec<u64> = (0..master.face_count())
        .flat_map(|f| {
            master
                .face(f)
                .nodes
                .iter()
                .map(|&n| master.node_tags()[n as usize])
        })
        .collect();
    master_nodes.sort_unstable();
    master_nodes.dedup();
    let counts = RankCounts {
        uncoupled_faces: uncoupled_faces.len(),
        ..counts
    };
    RankRows {
        rows,
        d,
        m,
        master_nodes,
        counts,
        warnings,
        uncoupled_faces,
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
