# With a cluster executor (profiles/slurm) these rules run where snakemake runs instead of as Slurm
# jobs: each reads a few CSV files and writes a table or a figure in a second or two, less than
# one submission and status poll costs. A local run is unaffected.


localrules:
    boundary_table,
    boundary_grid,
    c_per_threshold,
    fig1,
    fig2,
    fig3,
    fig4,
    fig5,
    fig6,
    fig7,
    figB8,
    figD9,
    figE10,
    table1,
    systems_table,
    c0_table,
    surrogate_southwell,
    surrogate_vs_full,
    versions,
    atlas_gather,
