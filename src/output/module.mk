# Layer: output. Modules and the objects of the modules each one uses.
MODULES += output_schedule listing progress results_gmsh results_vtu results_frd results_dat results_sta
$(OBJDIR)/output_schedule.o: $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
$(OBJDIR)/listing.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/blas_info.o $(OBJDIR)/contact_heat.o $(OBJDIR)/contact_results.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/output_schedule.o $(OBJDIR)/solver_codes.o $(OBJDIR)/strings.o
$(OBJDIR)/progress.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/results_gmsh.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/output_schedule.o
$(OBJDIR)/results_vtu.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/output_schedule.o $(OBJDIR)/strings.o
$(OBJDIR)/results_frd.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/output_schedule.o $(OBJDIR)/strings.o
$(OBJDIR)/results_dat.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/output_schedule.o
$(OBJDIR)/results_sta.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/model.o
