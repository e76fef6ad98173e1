//! Times the stages of condensing each part of a scene (assemble, order and
//! factorise, Schur complement) with a given interior ordering, and prints the factor's size and flops:
//! `cargo run --release --example condense_stages -- SCENE.toml OUT_DIR
//! [amd|nd|auto] [sequential|concurrent]`; with the last argument it times
//! `condense_parts` on one thread or two instead. OUT_DIR receives the mesh.

use std::path::{Path, PathBuf};
use std::time::Instant;

use faer::Par;
use subcontact::driver::load_mesh;
use subcontact::model::Model;
use subcontact::scene::Scene;
use subcontact::substructure::ordering::Ordering;
use subcontact::substructure::{
    assembly, condense_parts, interior_nodes, numbering, parts, schur::PartialCholesky, Condensation,
};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let scene = Scene::load(Path::new(&args[1]))?;
    let out = PathBuf::from(&args[2]);
    let which = args.get(3).map_or("auto", |s| s.as_str());
    let par = Par::Seq;
    faer::set_global_parallelism(Par::Seq);
    let (mesh, _, _) = load_mesh(&scene, &out, false)?;
    let model = Model::build(&mesh, &scene.model_spec())?;
    drop(mesh);
    if let Some(mode) = args.get(4) {
        // whole `condense` per part: one after the other ("sequential"), or two threads ("concurrent")
        let t = Instant::now();
        let threads = if mode == "concurrent" { 2 } else { 1 };
        let done: Vec<usize> =
            condense_parts(&model, parts(&model), threads, Condensation::Dense)?.iter().map(|c| c.nc).collect();
        println!("{mode}: condense of {} parts (nc {done:?}) {:.3}s", done.len(), t.elapsed().as_secs_f64());
        return Ok(());
    }
    for part in parts(&model) {
        let t = Instant::now();
        let (dof_of, ni, nc) = numbering(&model, &part);
        let a = assembly::assemble(&model, &part.cells, &dof_of, ni + nc)?;
        let t_asm = t.elapsed().as_secs_f64();
        let node_of = interior_nodes(&dof_of, model.nd, ni);
        let ordering = match which {
            "amd" => Ordering::Amd,
            "nd" => Ordering::NestedDissection,
            _ => Ordering::choose(ni, model.nd),
        };
        let t = Instant::now();
        subcontact::substructure::ordering::interior(&a.k, ni, &node_of, ordering)
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        let t_order = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let chol = PartialCholesky::factor(&a.k, ni, &node_of, ordering, par).map_err(|e| anyhow::anyhow!("{e}"))?;
        let t_fac = t.elapsed().as_secs_f64();
        let st = chol.stats();
        let t = Instant::now();
        let s = chol.schur(par);
        let t_schur = t.elapsed().as_secs_f64();
        let flops = nc as f64 * nc as f64 * nc as f64 / 3.0;
        // faer's dense Cholesky of the same size, for the GFLOP/s reference
        let t_llt = if nc > 0 {
            let mut m = faer::Mat::<f64>::from_fn(nc, nc, |i, j| s[i + j * nc]);
            for i in 0..nc {
                m[(i, i)] += 2.0 * chol.alpha();
            }
            let t = Instant::now();
            let _llt = m.llt(faer::Side::Lower).map_err(|e| anyhow::anyhow!("{e:?}"))?;
            t.elapsed().as_secs_f64()
        } else {
            0.0
        };
        println!(
            "{ordering:?} ni={ni} nc={nc} nnz(K)={} values(L)={:.3e} flops={:.3e} | assemble {t_asm:.3}s order {t_order:.3}s factor {t_fac:.3}s ({:.1} GFLOP/s) schur {t_schur:.3}s ({:.1} GFLOP/s) dense llt {t_llt:.3}s ({:.1} GFLOP/s) | s00={:.9e}",
            a.k.row_idx.len(),
            st.values as f64,
            st.flops,
            st.flops / t_fac / 1e9,
            flops / t_schur / 1e9,
            flops / t_llt / 1e9,
            s[0]
        );
    }
    Ok(())
}
