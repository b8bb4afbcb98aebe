# What accuracy costs in time: a study target (DESIGN.md, accuracy and cost).


rule accuracy_hertz:
    """Load and contact-radius error against wall time and dofs (report 6.1)."""
    output:
        data=f"{RESULTS}/accuracy/hertz.nc",
        figure=report(f"{RESULTS}/accuracy/hertz.png", category="accuracy",
                      caption="../report/accuracy.rst"),
    params:
        study=config.get("accuracy_study", {}),
    log:
        f"{RESULTS}/accuracy/logs/hertz.log",
    script:
        "../scripts/accuracy_hertz.py"
